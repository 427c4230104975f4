// A face index that names no point.
// expect error: index 7 in [0, 1, 7] names no point
// expect no-openscad: OpenSCAD builds what it can
polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0]], faces = [[0, 1, 7]]);
