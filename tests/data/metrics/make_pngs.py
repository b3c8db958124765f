# Writes the small PNGs that metrics_test reads: one per PNG colour type, plus a
# 16-bit file that readPng must refuse. Run from this folder: python3 make_pngs.py
import struct
import zlib

W, H = 3, 2


def chunk(kind, data):
    return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))


def write(name, bit_depth, colour_type, rows, plte=None):
    raw = b''.join(b'\x00' + bytes(r) for r in rows)  # filter type 0 on every row
    data = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, bit_depth, colour_type, 0, 0, 0))
    if plte:
        data += chunk(b'PLTE', bytes(plte))
    data += chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b'')
    with open(name, 'wb') as f:
        f.write(data)


def rgba(x, y):  # the same formula is in metrics_test.cpp (expectedPixel)
    return (40 * x + 100 * y + 5, 255 - 30 * x - 7 * y, (50 * x * y) % 256, 60 * x + 100 * y + 3)


PALETTE = [(10, 20, 30), (200, 100, 0), (0, 0, 255), (255, 255, 255)]
px = [[rgba(x, y) for x in range(W)] for y in range(H)]
write('rgb8.png', 8, 2, [[c for p in row for c in p[:3]] for row in px])
write('gray8.png', 8, 0, [[p[0] for p in row] for row in px])
write('graya8.png', 8, 4, [[c for p in row for c in (p[0], p[3])] for row in px])
write('palette8.png', 8, 3, [[(x + 3 * y) % 4 for x in range(W)] for y in range(H)],
      plte=[c for p in PALETTE for c in p])
write('rgb16.png', 16, 2, [[b for p in row for c in p[:3] for b in (c, c)] for row in px])
