#!/usr/bin/env python3
"""RMSE and PSNR of two 8-bit RGB(A) PNGs of one size (values over 255), and
with --diff OUT a difference image (|a - b| x 4). No libraries beyond the
standard ones: bench/dof_secondary_table.sh uses it."""
import math
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    at, idat = 8, b""
    while at < len(data):
        (length,) = struct.unpack(">I", data[at:at + 4])
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + length]
        at += 12 + length
        if kind == b"IHDR":
            width, height, _, colour = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
    raw, bpp = zlib.decompress(idat), (3 if colour == 2 else 4)
    stride, rows, prev, k = width * bpp, [], bytearray(width * bpp), 0
    for _ in range(height):
        kind, line = raw[k], bytearray(raw[k + 1:k + 1 + stride])
        k += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(width)])
        prev = line
    return rows


def write_png(path, rows):
    width, height = len(rows[0]), len(rows)
    raw = b"".join(b"\0" + bytes(v for px in row for v in px) for row in rows)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
                           + chunk(b"IEND", b""))


def main():
    a, b = read_png(sys.argv[1]), read_png(sys.argv[2])
    total, count = 0.0, 0
    for row_a, row_b in zip(a, b):
        for p, q in zip(row_a, row_b):
            for i in range(3):
                d = (p[i] - q[i]) / 255.0
                total += d * d
                count += 1
    rmse = math.sqrt(total / count)
    psnr = 20 * math.log10(1.0 / rmse) if rmse > 0 else float("inf")
    print("rmse=%.4f psnr=%.2fdB" % (rmse, psnr))
    if len(sys.argv) > 4 and sys.argv[3] == "--diff":
        write_png(sys.argv[4], [[tuple(min(255, 4 * abs(p[i] - q[i])) for i in range(3)) for p, q in zip(ra, rb)]
                                for ra, rb in zip(a, b)])


if __name__ == "__main__":
    main()
