#!/usr/bin/env python3
"""Writes the io/ test fixtures and fuzz seeds in this directory (run from anywhere).

Good files: cubes in every text/binary format, two cubes sharing an edge (a
non-manifold STL), a cube whose side faces are split into coplanar triangles.
Bad files: one per error case of docs/io.md. The .3mf and .json seeds are written
by `cellforge convert` (scripts/fuzz.sh and the tests make their own as needed)."""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

CORNERS = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def cube_triangles(lo=(0, 0, 0), hi=(1, 1, 1)):
    pts = [tuple(lo[k] if c[k] == 0 else hi[k] for k in range(3)) for c in CORNERS]
    tris = []
    for a, b, c, d in QUADS:
        tris.append((pts[a], pts[b], pts[c]))
        tris.append((pts[a], pts[c], pts[d]))
    return tris


def ascii_stl(tris, name="cube"):
    out = [f"solid {name}"]
    for t in tris:
        out.append("  facet normal 0 0 0\n    outer loop")
        for p in t:
            out.append("      vertex %r %r %r" % tuple(float(c) for c in p))
        out.append("    endloop\n  endfacet")
    out.append(f"endsolid {name}\n")
    return "\n".join(out).encode()


def binary_stl(tris, header=b"cellforge test"):
    data = header.ljust(80, b" ") + struct.pack("<I", len(tris))
    for t in tris:
        data += struct.pack("<3f", 0, 0, 0)
        for p in t:
            data += struct.pack("<3f", *p)
        data += b"\0\0"
    return data


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


cube = cube_triangles()
write("cube_ascii.stl", ascii_stl(cube))
write("cube_binary.stl", binary_stl(cube))
# A binary file whose header starts with "solid" (common; must still be binary).
write("cube_binary_solid_header.stl", binary_stl(cube, b"solid but binary"))
write("two_cubes_edge.stl", ascii_stl(cube + cube_triangles((1, 1, 0), (2, 2, 1)), "two_cubes"))
write("two_cubes_vertex.stl", binary_stl(cube + cube_triangles((1, 1, 1), (2, 2, 2))))
write("open_box.stl", ascii_stl(cube[2:], "open_box"))  # bottom face missing
flipped = cube[:11] + [tuple(reversed(cube[11]))]
write("flipped_triangle.stl", ascii_stl(flipped, "flipped"))

# OBJ: quads with v/vt/vn forms and negative indices; a wire and a point.
obj = ["# unit cube", "o cube"]
obj += ["v %d %d %d" % c for c in CORNERS]
obj += ["vt 0 0", "vt 1 0", "vt 1 1", "vn 0 0 1"]
forms = ["{v}", "{v}/1", "{v}//1", "{v}/2/1"]
for i, q in enumerate(QUADS):
    if i == 5:  # negative indices count back from the latest vertex
        obj.append("f " + " ".join(str(v - 8) for v in q))
    else:
        obj.append("f " + " ".join(forms[(i + k) % 4].format(v=v + 1) for k, v in enumerate(q)))
write("cube.obj", "\n".join(obj) + "\n")
write("wire_point.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nv 6 6 6\nf 1 2 3\nl 4 5\np 5\n")

off = ["OFF", "8 6 12"] + ["%d %d %d" % c for c in CORNERS]
off += ["4 " + " ".join(str(v) for v in q) for q in QUADS]
write("cube.off", "\n".join(off) + "\n")

# A cube with every face split into 4 coplanar triangles around its centre.
pts = [tuple(float(c) for c in p) for p in CORNERS]
faces = []
for q in QUADS:
    centre = tuple(sum(pts[v][k] for v in q) / 4 for k in range(3))
    pts.append(centre)
    c = len(pts) - 1
    for k in range(4):
        faces.append((q[k], q[(k + 1) % 4], c))
write("cube_split.obj", "\n".join(["v %r %r %r" % p for p in pts] +
                                 ["f %d %d %d" % tuple(i + 1 for i in f) for f in faces]) + "\n")

# Bad input, one file per case.
write("bad_empty.stl", b"")
write("bad_truncated.stl", binary_stl(cube)[:-30])
write("bad_oversized.stl", binary_stl(cube) + b"\0" * 7)
write("bad_huge_count.stl", b"x" * 80 + struct.pack("<I", 0xFFFFFFFF) + b"\0" * 50)
write("bad_nan_ascii.stl", ascii_stl(cube).replace(b"vertex 0.0 0.0 0.0", b"vertex nan 0.0 0.0", 1))
nan_bin = bytearray(binary_stl(cube))
nan_bin[84 + 12:84 + 16] = struct.pack("<f", float("nan"))
write("bad_nan_binary.stl", bytes(nan_bin))
write("bad_keyword.stl", b"solid x\n  facet normal 0 0 1\n    outer lop\n")
write("bad_index.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
write("bad_zero_index.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")
write("bad_inf.obj", b"v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n")
write("bad_utf8.obj", b"# caf\xc3\xa9 ok\nv 0 0 0\no name\xff\xfe\n")
write("bad_empty.obj", b"")
write("bad_count.off", b"OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n")
write("bad_huge_count.off", b"OFF\n999999999 1 0\n0 0 0\n")
write("bad_index.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")
write("bad_not_zip.3mf", b"<?xml version=\"1.0\"?><model/>")
write("bad_truncated.json", b'{"format":"cellforge-model","version":1,"groups":[{"name":"a"')
write("bad_format.json", b'{"format":"other","version":1}')

# ---- Real-file kinds (issue 19), one folder per what they exercise.
import math


def reversed_tris(tris):
    return [(a, c, b) for a, b, c in tris]


def uv_sphere(centre, r, n=16, m=8):
    """A closed UV sphere, outward: poles shared, the seam welded (i % n)."""
    def p(i, j):
        if j == 0:
            return (centre[0], centre[1], centre[2] + r)
        if j == m:
            return (centre[0], centre[1], centre[2] - r)
        th, ph = math.pi * j / m, 2 * math.pi * (i % n) / n
        return (centre[0] + r * math.sin(th) * math.cos(ph),
                centre[1] + r * math.sin(th) * math.sin(ph), centre[2] + r * math.cos(th))
    tris = []
    for j in range(m):
        for i in range(n):
            a, b, c, d = p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)
            if j > 0:
                tris.append((a, d, b))
            if j < m - 1:
                tris.append((b, d, c))
    return tris


def octahedron(centre, r):
    x, y, z = centre
    px, nx, py, ny, pz, nz = (x + r, y, z), (x - r, y, z), (x, y + r, z), (x, y - r, z), \
        (x, y, z + r), (x, y, z - r)
    return [(px, py, pz), (py, nx, pz), (nx, ny, pz), (ny, px, pz),
            (py, px, nz), (nx, py, nz), (ny, nx, nz), (px, ny, nz)]


def obj_text(points, faces):
    return "\n".join(["v %r %r %r" % tuple(float(c) for c in p) for p in points] +
                     ["f " + " ".join(str(i + 1) for i in f) for f in faces]) + "\n"


def sub(name, data):
    os.makedirs(os.path.join(HERE, os.path.dirname(name)), exist_ok=True)
    write(name, data)


big = cube_triangles((0, 0, 0), (10, 10, 10))
# Hollow solids: the inner shells face inward (cavities) or outward (nested solids).
sub("nested/cube_sphere_cavity.stl",
    ascii_stl(big + reversed_tris(uv_sphere((5, 5, 5), 3)), "hollow"))
sub("nested/cube_octahedron_cavity.stl",  # 1000 - 4/3 * 3^3 = 964
    binary_stl(big + reversed_tris(octahedron((5, 5, 5), 3))))
sub("nested/nested_cubes.stl",  # 1000 - 216 + 8 = 792
    ascii_stl(big + reversed_tris(cube_triangles((2, 2, 2), (8, 8, 8))) +
              cube_triangles((4, 4, 4), (6, 6, 6)), "nested"))
sub("nested/nested_cubes_outward.stl",  # every shell outward: repair_orientation gives 792
    ascii_stl(big + cube_triangles((2, 2, 2), (8, 8, 8)) + cube_triangles((4, 4, 4), (6, 6, 6)),
              "nested_outward"))
sub("nested/cavity_alone.stl", ascii_stl(reversed_tris(cube), "cavity"))  # bounds no cell

# Back-to-back faces: zero-thickness pairs and fins on the edges of a solid.
unit = [tuple(float(c) for c in p) for p in CORNERS]
unit_faces = [(q[0], q[1], q[2]) for q in QUADS] + [(q[0], q[2], q[3]) for q in QUADS]
two = unit + [(p[0] + 1, p[1], p[2]) for p in unit]
sub("back_to_back/two_cubes_face.obj",  # the common face twice, once per cube
    obj_text(two, unit_faces + [tuple(i + 8 for i in f) for f in unit_faces]))
centre = unit + [(0.5, 0.5, 0.5)]
sub("back_to_back/pair_in_cube.obj",  # a pair on cube edge 0-1, inside the cube
    obj_text(centre, unit_faces + [(0, 1, 8), (1, 0, 8)]))
sub("back_to_back/fin_in_cube.obj", obj_text(centre, unit_faces + [(0, 1, 8)]))
sub("back_to_back/diagonal_wall.obj",  # a pair from edge 0-4 to edge 3-7: two prisms
    obj_text(unit, unit_faces + [(0, 3, 7), (0, 7, 4), (0, 7, 3), (0, 4, 7)]))

# Precision: -0 and coordinates 6 decimals cannot hold.
sub("precision/negative_zero.obj",
    obj_text([(-0.0, -0.0, -0.0), (1.0, -0.0, 0.0), (0.0, 1.0, -0.0), (-0.0, 0.0, 1.0)],
             [(0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3)]))
tiny = [(1e-9 * x + 0.1, 1e-9 * y + 0.2, 1e-9 * z + 1.0 / 3) for x, y, z in CORNERS]
sub("precision/tiny_cube.obj", obj_text(tiny, [q for q in QUADS]))
