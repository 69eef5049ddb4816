// Placeholder entry point until the Super4PCS tool lands (issue 4).
#include <cstdio>
int main() { std::fprintf(stderr, "brick_pose_register: not built yet\n"); return 2; }
