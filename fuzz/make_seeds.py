#!/usr/bin/env python3
"""Writes the seed corpus under fuzz/corpus/<target>/ (run from anywhere).

The targets decode their input with clang's FuzzedDataProvider, which takes
integers and floats from the END of the buffer (first value = last bytes, most
significant byte first) and strings/remaining bytes from the front. Seeds are
encoded the same way, so each one is a meaningful scene (a plate the front end
finds, a face the correction accepts, ...) from which the fuzzer mutates,
rather than noise it would need minutes to turn into structure.
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


class Encoder:
    """Builds a buffer that FuzzedDataProvider decodes into the given values."""

    def __init__(self):
        self.front = b""
        self.tail = []  # bytes in the order they are consumed from the end

    def int_in(self, value, low, high):
        span, shift, count = high - low, 0, 0
        while shift < 64 and (span >> shift) > 0:
            shift, count = shift + 8, count + 1
        offset = value - low
        assert 0 <= offset <= span
        for i in reversed(range(count)):
            self.tail.append((offset >> (8 * i)) & 0xFF)

    def boolean(self, value):
        self.int_in(1 if value else 0, 0, 255)

    def probability(self, p):
        self.int_in(min(int(p * (2**64 - 1)), 2**64 - 1), 0, 2**64 - 1)

    def float_in(self, value, low, high):
        # Ranges used here never overflow a double, so no extra bool is read.
        self.probability((value - low) / (high - low))

    def fuzz_double(self, value, low, high):
        """fuzz_support.h consumeDouble, ordinary branch."""
        self.int_in(1, 0, 7)
        self.float_in(value, low, high)

    def string(self, text):
        self.front += text.encode() + b"\\\n"  # '\' + other char ends the string

    def bytes(self):
        return self.front + bytes(reversed(self.tail))


def write(target, name, data):
    folder = os.path.join(HERE, "corpus", target)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, name), "wb") as f:
        f.write(data)


# --- fuzz_front_end: plates on a background plane (96x72, fx 100) --------
GREEN, RED, BLUE, ORANGE, RAW = 1, 0, 2, 3, 4


def front_end_seed(plates, width=96, height=72, fx=100.0, region_growing=False, scaled=True, background_mm=1300):
    e = Encoder()
    e.boolean(region_growing)
    e.boolean(scaled)
    e.boolean(True)  # merge face pieces
    e.int_in(width, 1, 96)
    e.int_in(height, 1, 72)
    e.float_in(fx, 20.0, 300.0)
    e.boolean(True)  # fy = fx
    e.float_in(0.0, -8.0, 8.0)
    e.float_in(0.0, -8.0, 8.0)
    e.int_in(background_mm, 0, 65535)
    e.int_in(len(plates), 0, 4)
    for (u0, v0, u1, v1, color, depth_mm, slope_u, slope_v) in plates:
        e.int_in(u0, 0, width - 1)
        e.int_in(v0, 0, height - 1)
        e.int_in(u1, u0, width - 1)
        e.int_in(v1, v0, height - 1)
        e.int_in(color, 0, 4)
        if color == RAW:
            for channel in (90, 90, 90):
                e.int_in(channel, 0, 255)
        e.int_in(depth_mm, 0, 65535)
        e.int_in(slope_u, -40, 40)
        e.int_in(slope_v, -40, 40)
    return e.bytes()


write("fuzz_front_end", "green_plate", front_end_seed([(18, 26, 77, 45, GREEN, 1000, 0, 0)]))
write("fuzz_front_end", "red_plate_tilted", front_end_seed([(30, 20, 59, 39, RED, 1000, 2, 0)]))
write("fuzz_front_end", "two_plates", front_end_seed([(5, 5, 64, 24, GREEN, 1000, 0, 0), (40, 40, 69, 59, RED, 1100, 0, 0)]))
write("fuzz_front_end", "occluded_plate",
      front_end_seed([(18, 26, 77, 45, GREEN, 1000, 0, 0), (45, 20, 49, 50, RAW, 900, 0, 0)]))
write("fuzz_front_end", "region_growing", front_end_seed([(18, 26, 77, 45, GREEN, 1000, 0, 0)], region_growing=True))
write("fuzz_front_end", "default_thresholds", front_end_seed([(10, 10, 89, 69, BLUE, 700, 0, 0)], scaled=False))


# --- fuzz_frame_builder: small valid frames of each encoding pair ---------
def frame_seed(width, height, color_encoding, depth_encoding, pixels, pad=0):
    encodings = ["rgb8", "bgr8", "rgba8", "bgra8", "16UC1", "mono16", "32FC1"]
    e = Encoder()
    e.string("camera_color_optical_frame")
    e.int_in(width, -2, 48)
    e.int_in(height, -2, 48)
    e.int_in(1, 0, 7)  # depth the same size
    e.int_in(encodings.index(color_encoding), 0, 10)
    e.int_in(2, 0, 7)  # step = row + padding
    e.int_in(pad, 0, 9)
    e.int_in(encodings.index(depth_encoding), 0, 10)
    e.int_in(2, 0, 7)
    e.int_in(pad, 0, 9)
    e.int_in(1, 0, 7)  # camera size matches
    e.fuzz_double(40.0, -10.0, 2000.0)
    e.fuzz_double(40.0, -10.0, 2000.0)
    e.fuzz_double(width / 2.0, -100.0, 200.0)
    e.fuzz_double(height / 2.0, -100.0, 200.0)
    e.int_in(1_700_000_000 * 10**9, -(2**63), 2**63 - 1)
    e.front += pixels
    return e.bytes()


millimetres = struct.pack("<8H", 1000, 0, 1200, 65535, 800, 1000, 1000, 999) * 2
metres = struct.pack("<8f", 1.0, 0.0, float("nan"), float("inf"), -1.0, 1.5, 2.0, 1e-30)
write("fuzz_frame_builder", "rgb8_16uc1", frame_seed(4, 4, "rgb8", "16UC1", millimetres))
write("fuzz_frame_builder", "bgra8_32fc1", frame_seed(4, 2, "bgra8", "32FC1", metres, pad=3))
write("fuzz_frame_builder", "bgr8_mono16", frame_seed(8, 8, "bgr8", "mono16", millimetres, pad=1))
write("fuzz_frame_builder", "rgba8_16uc1_1x1", frame_seed(1, 1, "rgba8", "16UC1", struct.pack("<H", 1000)))


# --- fuzz_super4pcs: a model face and the same face moved -----------------
def super4pcs_seed(source, target, normals=False):
    e = Encoder()
    e.int_in(20, 1, 50)  # max_bases
    e.float_in(0.9, 0.05, 1.0)  # overlap
    e.float_in(0.004, 0.0005, 0.05)  # delta_m
    e.int_in(32, 4, 64)
    e.int_in(32, 4, 64)
    e.int_in(2, 0, 5)  # refine iterations
    e.int_in(1, 0, 255)  # seed
    e.boolean(normals)
    for points in (source, target):
        e.int_in(len(points), 0, 48)
        for point in points:
            for coordinate_mm in point:
                e.int_in(1, 0, 31)  # grid coordinate
                e.int_in(coordinate_mm, -500, 500)
            if normals:
                for coordinate in (0, 0, 500):
                    e.int_in(1, 0, 31)
                    e.int_in(coordinate, -500, 500)  # normalised by the target
                e.int_in(1, 0, 15)
    return e.bytes()


plate = [(x, y, 0) for x in range(-150, 151, 50) for y in range(-100, 101, 50)]  # 7x5 grid, 0.3x0.2 m
moved = [(y + 20, -x + 10, 300) for (x, y, _) in plate]  # quarter turn, shifted
write("fuzz_super4pcs", "plate_quarter_turn", super4pcs_seed(plate, moved))
write("fuzz_super4pcs", "plate_with_normals", super4pcs_seed(plate[:20], moved[:20], normals=True))
write("fuzz_super4pcs", "collinear", super4pcs_seed([(i * 10, 0, 0) for i in range(8)], [(0, i * 10, 0) for i in range(8)]))


# --- fuzz_pose_correction: a face seen head-on, registration slightly off --
def correction_seed(full_mode, quaternion_wxyz, translation, t1, t2_offset, normal, brick=1):
    e = Encoder()
    e.boolean(full_mode)
    e.int_in(brick, 0, 3)
    e.int_in(1, 0, 7)  # catalogue dimensions
    e.int_in(1, 0, 3)  # rigid pose from a quaternion
    for value in quaternion_wxyz:
        e.fuzz_double(value, -1, 1)
    for value in translation:
        e.fuzz_double(value, -3.0, 3.0)
    for value in t1:
        e.fuzz_double(value, -3.0, 3.0)
    e.int_in(1, 0, 3)  # t2 = t1 + offset
    for value in t2_offset:
        e.fuzz_double(value, -2.0, 2.0)
    e.boolean(True)  # centroid at the midpoint
    for value in normal:
        e.fuzz_double(value, -1.0, 1.0)
    return e.bytes()


flip_x = (0.0, 1.0, 0.0, 0.0)  # brick z toward the camera
write("fuzz_pose_correction", "head_on_full", correction_seed(True, flip_x, (0.0, 0.0, 1.0), (-0.3, 0.0, 1.0), (0.6, 0.01, 0.0), (0.0, 0.0, -1.0)))
write("fuzz_pose_correction", "head_on_paper", correction_seed(False, flip_x, (0.01, 0.0, 1.0), (-0.3, 0.0, 1.0), (0.6, -0.02, 0.0), (0.0, 0.0, -1.0)))
write("fuzz_pose_correction", "tilted_full", correction_seed(True, (0.1, 0.99, 0.05, 0.0), (0.2, -0.1, 1.5), (0.0, -0.1, 1.5), (0.4, 0.2, 0.05), (0.05, 0.1, -1.0)))
