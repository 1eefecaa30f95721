#!/usr/bin/env python3
"""The test images of tests/data/textures (tests/test_texture.c), the same
bytes on every run.

  python3 make.py          the PNGs, and the pictures the JPEGs are made of
  (the JPEGs, with cjpeg and djpeg of libjpeg-turbo-progs:)
  cjpeg -quality 90 -outfile tex.jpg tex-src.ppm            19 x 13, 4:2:0
  cjpeg -quality 90 -grayscale -outfile grey.jpg tex-src.ppm
  cjpeg -quality 85 -outfile big.jpg big-src.ppm            67 x 45, 4:2:0
  cjpeg -quality 85 -progressive -outfile prog.jpg big-src.ppm
  djpeg -dct int -outfile NAME-djpeg.ppm NAME.jpg           (-pnm for grey)
  python3 make.py broken   the refused files, from the good ones
"""
import struct
import sys
import zlib


def chunk(kind, data):
    return (struct.pack(">I", len(data)) + kind + data +
            struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))


def png_bytes(width, height, depth, color, rows, extra=b""):
    """rows: each scanline's bytes (filter 0 added here)."""
    ihdr = struct.pack(">IIBBBBB", width, height, depth, color, 0, 0, 0)
    raw = b"".join(b"\0" + r for r in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + extra +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def write(path, data):
    with open(path, "wb") as f:
        f.write(data)


def good():
    # 3 x 2 RGBA, 8 bits, with a gAMA of 1.0 that must not change the texels
    write("rgba8.png", png_bytes(
        3, 2, 8, 6,
        [bytes([255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0]),
         bytes([1, 2, 3, 4, 128, 128, 128, 255, 250, 251, 252, 253])],
        chunk(b"gAMA", struct.pack(">I", 100000))))
    # 2 x 2 RGBA, 16 bits, no gAMA: 0x8080 must read 0x80 (libpng's
    # simplified API would take the file for linear light and give 0xBC)
    w16 = lambda *v: b"".join(struct.pack(">H", x) for x in v)
    write("rgba16.png", png_bytes(
        2, 2, 16, 6,
        [w16(0x8080, 0x8080, 0x8080, 0x8080, 0xFFFF, 0x0000, 0x1234, 0xFFFF),
         w16(0x0080, 0x007F, 0xFF7F, 0xFF80, 0x4000, 0xC000, 0x8000, 0x7FFF)]))
    # 4 x 1 palette, 2 bits, with a tRNS giving entry 1 alpha 0x40
    write("palette.png", png_bytes(
        4, 1, 2, 3, [bytes([0b00011011])],
        chunk(b"PLTE", bytes([10, 20, 30, 200, 100, 50, 0, 0, 0, 255, 255, 255])) +
        chunk(b"tRNS", bytes([255, 0x40]))))
    # 2 x 1 grey and alpha, 8 bits
    write("greya.png", png_bytes(2, 1, 8, 4, [bytes([0x33, 0x80, 0xCC, 0xFF])]))

    # 19 x 13 RGB: colour bands and a gradient
    w, h = 19, 13
    px = bytearray()
    for y in range(h):
        for x in range(w):
            if y < 4:
                px += bytes([(255, 0, 0), (0, 255, 0), (0, 0, 255),
                             (255, 255, 0)][x * 4 // w])
            else:
                px += bytes([x * 255 // (w - 1), y * 255 // (h - 1), 128])
    write("tex-src.ppm", b"P6\n%d %d\n255\n" % (w, h) + bytes(px))
    # 67 x 45 RGB: gradients and noise (a linear congruential sequence),
    # detail for every SIMD routine of the decoder
    w, h, s = 67, 45, 7
    px = bytearray()
    for y in range(h):
        for x in range(w):
            s = (s * 1103515245 + 12345) & 0x7FFFFFFF
            px += bytes([x * 255 // (w - 1), y * 255 // (h - 1),
                         (x * y * 7 + (s >> 16) % 64) & 255])
    write("big-src.ppm", b"P6\n%d %d\n255\n" % (w, h) + bytes(px))


def broken():
    ok = open("rgba8.png", "rb").read()
    # the IDAT's CRC changed
    idat = ok.index(b"IDAT") + 4
    crc = idat + struct.unpack(">I", ok[idat - 8:idat - 4])[0]
    write("corrupt.png", ok[:crc] + bytes([ok[crc] ^ 0xFF]) + ok[crc + 1:])
    # cut in the middle of the IDAT
    write("truncated.png", ok[:idat + 6])
    # a header of 8193 x 1 (nothing after: refused before any texel)
    write("toolarge.png", b"\x89PNG\r\n\x1a\n" +
          chunk(b"IHDR", struct.pack(">IIBBBBB", 8193, 1, 8, 6, 0, 0, 0)))
    jpg = open("tex.jpg", "rb").read()
    write("truncated.jpg", jpg[:len(jpg) // 2])
    # the frame header (SOF0) says 19 x 9000
    sof = jpg.index(b"\xff\xc0")
    write("toolarge.jpg", jpg[:sof + 5] + struct.pack(">H", 9000) + jpg[sof + 7:])
    # three bytes before the end marker: libjpeg warns and would go on
    write("extraneous.jpg", jpg[:-2] + b"abc" + jpg[-2:])
    # the start of image and at once its end
    write("noimage.jpg", b"\xff\xd8\xff\xd9")


if __name__ == "__main__":
    broken() if sys.argv[1:] == ["broken"] else good()
