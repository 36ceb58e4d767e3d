#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz harnesses (fuzz/corpus/<harness>/): small hand-made valid
and near-valid files. Run from anywhere: python3 fuzz/make_seeds.py. The files are committed; this
script says how they were made and remakes them (deterministically)."""
import os, random, struct

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")


def put(harness, name, data):
    d = os.path.join(ROOT, harness)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


# ---- PLY -----------------------------------------------------------------------------------
PTS = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1.5, -2.25, 3e2)]
TRIS = [(0, 1, 2), (0, 2, 3), (1, 2, 3)]


def ply_ascii_cloud():
    s = "ply\nformat ascii 1.0\ncomment made by fuzz/make_seeds.py\nelement vertex %d\n" % len(PTS)
    s += "property float x\nproperty float y\nproperty float z\nproperty int station\nend_header\n"
    return s + "".join("%g %g %g %d\n" % (x, y, z, i % 2) for i, (x, y, z) in enumerate(PTS))


def ply_ascii_mesh():
    s = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
    s += "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float quality\n"
    s += "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    s += "0 0 0 255 0 0 0.5\n1 0 0 0 255 0 1\n1 1 0 0 0 255 2\n0 1 0 9 9 9 3\n"
    return s + "3 0 1 2\n4 0 1 2 3\n"


def ply_binary_cloud(endian):
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    s = "ply\nformat %s 1.0\nelement vertex %d\nproperty double x\nproperty double y\nproperty double z\n" % (fmt, len(PTS))
    s += "property int station\nproperty int mesh\nproperty double scanner_x\nproperty double scanner_y\n"
    s += "property double scanner_z\nend_header\n"
    b = s.encode()
    for i, p in enumerate(PTS):
        b += struct.pack(endian + "3dii3d", *p, i, 7, 10, 20, 30)
    return b


def ply_binary_mesh(endian):
    fmt = "binary_little_endian" if endian == "<" else "binary_big_endian"
    s = "ply\nformat %s 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n" % fmt
    s += "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
    s += "element face 3\nproperty list uchar uint vertex_indices\nend_header\n"
    b = s.encode()
    for p in PTS[:4]:
        b += struct.pack(endian + "3f", *p)
    b += struct.pack(endian + "ii", 0, 1)
    for t in TRIS:
        b += struct.pack(endian + "B3I", 3, *t)
    return b


put("ply", "ascii_cloud.ply", ply_ascii_cloud())
put("ply", "ascii_mesh.ply", ply_ascii_mesh())
put("ply", "binary_le_cloud.ply", ply_binary_cloud("<"))
put("ply", "binary_be_cloud.ply", ply_binary_cloud(">"))
put("ply", "binary_le_mesh.ply", ply_binary_mesh("<"))
put("ply", "binary_be_mesh.ply", ply_binary_mesh(">"))
put("ply", "truncated_binary.ply", ply_binary_cloud("<")[:-13])
put("ply", "huge_count.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1099511627776\n"
    "property float x\nproperty float y\nproperty float z\nend_header\n\0\0\0\0")
put("ply", "ascii_nan.ply", ply_ascii_cloud().replace("1.5", "nan"))
put("ply", "bad_index.ply", ply_ascii_mesh().replace("3 0 1 2\n", "3 0 1 9\n"))


# ---- LAS -----------------------------------------------------------------------------------
def las(version_minor, point_format, points, scale=0.01, count=None, extra_header=b""):
    record = {0: 20, 1: 28, 2: 26, 3: 34, 6: 30, 7: 36}[point_format]
    header_size = {2: 227, 3: 235, 4: 375}[version_minor]
    n = len(points) if count is None else count
    h = b"LASF" + struct.pack("<HH", 0, 0) + b"\0" * 16 + struct.pack("<BB", 1, version_minor)
    h += b"treesketch seed".ljust(32, b"\0") + b"make_seeds.py".ljust(32, b"\0")
    h += struct.pack("<HHHIIBHI", 1, 2026, header_size, header_size, 0, point_format, record,
                     n if point_format < 6 else 0)
    h += struct.pack("<5I", n, 0, 0, 0, 0)
    h += struct.pack("<3d", scale, scale, scale) + struct.pack("<3d", 100.0, 200.0, 0.0)
    h += struct.pack("<6d", 1, -1, 1, -1, 1, -1)
    if version_minor >= 3:
        h += struct.pack("<Q", 0)
    if version_minor >= 4:
        h += struct.pack("<QIQ", 0, 0, n) + struct.pack("<15Q", n, *([0] * 14))
    assert len(h) == header_size, len(h)
    body = b""
    for (x, y, z) in points:
        body += struct.pack("<3i", x, y, z) + b"\0" * (record - 12)
    return h + extra_header + body


P = [(0, 0, 0), (100, 0, 5), (0, 100, 10), (-100, -100, 2000000000), (7, 8, 9)]
put("las", "v12_format0.las", las(2, 0, P))
put("las", "v12_format3.las", las(2, 3, P, scale=0.001))
put("las", "v13_format1.las", las(3, 1, P))
put("las", "v14_format6.las", las(4, 6, P))
put("las", "truncated.las", las(2, 0, P)[:-7])
put("las", "count_too_big.las", las(2, 0, P, count=4000000000))
put("las", "zero_scale.las", las(2, 0, P, scale=0.0))

# ---- LAZ (see laz_fuzz.cpp) -----------------------------------------------------------------
def tiny_laz(point_format=0, items=((6, 20, 2),), compressor=1, points=((1000, -2000, 3000),)):
    """A LAZ of point-wise compressor 1 (no chunk table): the first point of its one stream is raw."""
    vlr_body = struct.pack("<HHBBHII", compressor, 0, 3, 4, 3, 0, 50000) + struct.pack("<qqH", -1, -1, len(items))
    vlr_body += b"".join(struct.pack("<HHH", *it) for it in items)
    vlr = b"\0\0" + b"laszip encoded".ljust(16, b"\0") + struct.pack("<HH", 22204, len(vlr_body))
    vlr += b"\0" * 32 + vlr_body
    record = sum(it[1] for it in items)
    f = bytearray(las(2, point_format, [], count=len(points)))
    struct.pack_into("<IIBH", f, 96, 227 + len(vlr), 1, 0x80 | point_format, record)
    body = b"".join(struct.pack("<3i", *p) + b"\0" * (record - 12) for p in points)
    return bytes(f) + vlr + body + b"\0" * 4


put("laz", "tiny_point10.laz", tiny_laz())
put("laz", "tiny_gps_rgb.laz", tiny_laz(3, ((6, 20, 2), (7, 8, 2), (8, 6, 2))))
put("laz", "bad_version.laz", tiny_laz(items=((6, 20, 1),)))
lrnd = random.Random(7)
# Chunk inputs: format index, extra bytes, variant, count (u16), then the chunk (a raw first
# record, then coded bytes; layered chunks: count and layer sizes after the first record).
for fmt in range(7):
    record = [20, 28, 26, 34, 30, 36, 38][fmt] + fmt % 4
    head = bytes([fmt, fmt % 4, fmt]) + struct.pack("<H", 50 + 10 * fmt)
    first = bytes(lrnd.randrange(256) for _ in range(record))
    if fmt >= 4:  # layered: point count, then 9 POINT14 layer sizes (+ RGB, NIR, extra bytes)
        layers = 9 + (fmt == 5) + 2 * (fmt == 6) + fmt % 4
        sizes = [40] * layers
        first += struct.pack("<I", 50 + 10 * fmt) + b"".join(struct.pack("<I", n) for n in sizes)
        rest = bytes(lrnd.randrange(256) for _ in range(sum(sizes)))
    else:
        rest = bytes(lrnd.randrange(256) for _ in range(400))
    put("laz", "chunk%d.bin" % fmt, head + first + rest)

# ---- XYZ -----------------------------------------------------------------------------------
put("xyz", "plain.xyz", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n1.5 -2.25 300\n")
put("xyz", "csv_header.csv", "X,Y,Z,Intensity\n0,0,0,1\n1,0,0,2\n0,1,0,3\n0,0,1,4\n")
put("xyz", "semicolon_crlf.txt", "# comment\r\n5\r\n1;2;3\r\n4;5;6\r\n7;8;9\r\n1e3;-2e-3;+3\r\n")
put("xyz", "tabs_comments.pts", "// header\n0\t0\t0\t255 0 0\n\n1\t1\t1\n2\t2\t2\n# mid\n3\t3\t3\n")
put("xyz", "utm.xyz", "512345.678901 5432109.876543 123.456\n512345.1 5432109.2 123.3\n"
    "512346 5432110 124\n512347 5432111 125\n")
put("xyz", "decimal_comma.txt", "1,5;2,5;3,5\n1,5;2,5;3,5\n1,5;2,5;3,5\n1,5;2,5;3,5\n")
put("xyz", "short_line.xyz", "0 0 0\n1 1\n2 2 2\n3 3 3\n")
put("xyz", "extremes.xyz", "1e308 -1e308 4.9e-324\n1e-300 0 -0\n2.2250738585072014e-308 1 1\n1e309 0 0\n")

# ---- OBJ -----------------------------------------------------------------------------------
put("obj", "triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
put("obj", "quad_slashes.obj", "# seed\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1\n"
    "vt 0 0\nvn 0 0 1\ng group\nusemtl m\ns off\nf 1/1/1 2/1/1 3/1/1 4/1/1\nf 1//1 3//1 4//1\n")
put("obj", "negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1 0.5 0.5 0.5\nf -4 -3 -2\nf -1 -2 -3\nl 1 2\n")
put("obj", "bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")
put("obj", "no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")
put("obj", "crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n")

# ---- sketch files --------------------------------------------------------------------------
CAM = ('{"view":[1,0,0,0,0,1,0,0,0,0,1,-10,0,0,0,1],'
       '"projection":[1,0,0,0,0,1.6,0,0,0,0,-1.0002,-0.20002,0,0,-1,0],"viewport":[0,0,1280,800]}')
PARAMS = '{"sliceHalfThickness":0.05,"lineEpsilon":0.25,"lineEpsilonStep":0.25,"enabled":true}'
put("sketch_read", "screen_nodes.json",
    '{"format":"treesketch-sketch","version":1,"up":"y","defaults":%s,"cameras":[%s],"nodes":['
    '{"id":0,"parent":-1,"camera":0,"screen":[640,700],"params":%s},'
    '{"id":1,"parent":0,"camera":0,"screen":[640,400],"params":{"maxGrowthSteps":3}},'
    '{"id":2,"parent":1,"camera":0,"screen":[500,200],"params":{"enabled":false}}]}' % (PARAMS, CAM, PARAMS))
put("sketch_read", "point_nodes.json",
    '{"format":"treesketch-sketch","version":1,"up":"z","defaults":%s,"cameras":[],"nodes":['
    '{"id":0,"parent":-1,"point":[0,0,0],"normal":[0,0,1],"params":{}},'
    '{"id":4,"parent":0,"point":[0,0,1.5],"normal":[0.1,0,1],"params":{},'
    '"circle":{"centre":[0,0,1.5],"radius":0.12}},'
    '{"id":9,"parent":4,"point":[0.3,0,2],"normal":[1,0,1],"params":{"lineEpsilon":1e-3}}]}' % PARAMS)
put("sketch_read", "lassos.json",
    '{"format":"treesketch-sketch","version":2,"up":"y","defaults":%s,"cameras":[%s],'
    '"notWood":[{"camera":0,"polygon":[[0,0],[640,0],[640,800]]},'
    '{"camera":0,"wood":true,"polygon":[[100,100],[900,100],[900,700],[100,700]]}],'
    '"nodes":[{"id":0,"parent":-1,"camera":0,"screen":[640,700],"params":%s}]}' % (PARAMS, CAM, PARAMS))
put("sketch_read", "camera.json", CAM)
put("sketch_read", "cycle.json",
    '{"format":"treesketch-sketch","version":1,"up":"y","cameras":[],"nodes":['
    '{"id":0,"parent":1,"point":[0,0,0],"normal":[0,1,0]},{"id":1,"parent":0,"point":[0,1,0],"normal":[0,1,0]}]}')
put("sketch_read", "bad_json.json", '{"format":"treesketch-sketch","version":1,"nodes":[{"id":0,}]}')
put("sketch_read", "huge_number.json",
    '{"format":"treesketch-sketch","version":1,"up":"y","cameras":[],"nodes":['
    '{"id":0,"parent":-1,"point":[1e999,0,0],"normal":[0,1,0]}]}')

# ---- sketch round trip: bytes decoded as edits (see sketch_roundtrip_fuzz.cpp) -----------------
def small(v):  # nextDouble mode < 128: int8 / 16
    return bytes([0, int(round(v * 16)) & 0xFF])


def vec(x, y, z):
    return small(x) + small(y) + small(z)


def params(a=0.5, b=1.0, c=0.25, flags=0):
    return small(a) + small(b) + small(c) + bytes([flags])


def point_node(parent, p, n):
    return bytes([2, parent]) + vec(*p) + vec(*n) + params()


seed = bytes([0]) + params()
seed += point_node(255, (0, 0, 0), (0, 1, 0))
seed += point_node(0, (0, 1, 0), (0, 1, 0.5))
seed += point_node(1, (0.5, 2, 0), (1, 1, 0))
seed += bytes([7, 1]) + vec(0, 1, 0) + small(0.25)  # kept circle on node 1
put("sketch_roundtrip", "point_tree.bin", seed)
cam = bytes([0, 0, 0]) + vec(0, 1, 5) + vec(0, 1, 0) + small(2) + small(2) + small(0) + small(0) + small(7) + small(7)
screen = bytes([1, 255, 0]) + small(3) + small(3) + params() + bytes([1, 0, 0]) + small(3) + small(1) + params()
put("sketch_roundtrip", "camera_screen.bin", bytes([1]) + params() + cam + screen)
rnd = random.Random(19)
for i in range(4):
    put("sketch_roundtrip", "random%d.bin" % i, bytes(rnd.randrange(256) for _ in range(64 + 64 * i)))

# ---- format sniffer: first byte = extension index (see file_sniff_fuzz.cpp) -------------------
EXT = [".ply", ".obj", ".las", ".xyz", ".txt", ".csv", ".pts", ".PLY", ".Las", ".laz", ".dat", ""]
put("file_sniff", "ply.bin", bytes([0]) + ply_binary_cloud("<"))
put("file_sniff", "ply_mesh.bin", bytes([7]) + ply_ascii_mesh().encode())
put("file_sniff", "obj.bin", bytes([1]) + b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
put("file_sniff", "las.bin", bytes([2]) + las(2, 0, P))
put("file_sniff", "las14.bin", bytes([8]) + las(4, 6, P))
put("file_sniff", "laz.bin", bytes([9]) + las(2, 0, P))
put("file_sniff", "xyz.bin", bytes([3]) + b"0 0 0\n1 0 0\n0 1 0\n0 0 1\n")
put("file_sniff", "csv.bin", bytes([5]) + b"x,y,z\n0,0,0\n1,0,0\n0,1,0\n0,0,1\n")
put("file_sniff", "unknown.bin", bytes([10]) + b"0 0 0\n")
put("file_sniff", "noext.bin", bytes([11]) + b"ply\n")

# ---- closest point: bytes decoded as a mesh and queries (see closest_point_fuzz.cpp) ----------
def huge(mantissa, exponent):  # nextDouble mode 128..223: int16 mantissa * 10^e
    e = max(0, min(255, round((exponent + 330) * 255 / 640)))
    return bytes([128, e]) + struct.pack("<h", mantissa)


def vertex_new(x, y, z):
    return bytes([0]) + x + y + z


unit = vertex_new(small(0), small(0), small(0)) + vertex_new(small(1), small(0), small(0)) + \
    vertex_new(small(0), small(1), small(0))
tri = bytes([1, 0, 1, 2])
far = vertex_new(huge(1, 30), huge(-1, 30), huge(1, 30))
put("closest_point", "unit_far_query.bin", bytes([0]) + unit + tri + bytes([1]) + far + far + bytes([0]))
tiny = vertex_new(huge(1, -300), huge(2, -300), huge(3, -300))
put("closest_point", "tiny_mesh.bin", bytes([0]) + tiny + bytes([200]) + bytes([255, 0]) + tri + bytes([0]) + tiny + bytes([0]))
degen = vertex_new(small(1), small(1), small(1)) + bytes([130]) + bytes([129])  # repeated vertices
put("closest_point", "degenerate.bin", bytes([0]) + degen + tri + bytes([2]) + unit + bytes([1]) + small(0.5))
big = vertex_new(huge(3, 38), huge(1, 38), huge(-2, 38))
put("closest_point", "beyond_float.bin", bytes([0]) + big + unit[7:] + tri + bytes([0]) + big + bytes([0]))
for i in range(4):
    put("closest_point", "random%d.bin" % i, bytes(rnd.randrange(256) for _ in range(48 + 48 * i)))
