// import() of DXF: a closed LWPOLYLINE square 10 x 10 with a CIRCLE hole of radius 2
// ($fn = 4: a square of area 8) on layer "plate"; a triangle of three LINEs (legs 4
// and 3) on "tri"; on "frame" a closed LWPOLYLINE 6 x 6 holding a half disc (an ARC of
// 180 degrees, $fn = 4: 2 segments, and a LINE), a hole: 36 - 4. The DIMENSION entity
// carries no outline. Every coordinate is on OpenSCAD's 1/1024 grid already.
// expect volume: 130
// expect counts: volumes=3
linear_extrude(1) import("data/plate.dxf", $fn = 4);
