// dxf_dim() measures a DIMENSION of a DXF file by its name (group 1) and type
// (group 70 & 7), and dxf_cross() finds where two lone lines of a layer cross; both
// take origin and scale as import() does. data/dims.dxf, checked by hand: width,
// rotated at 0° from (0, 0) to (30, 5): 30; height, rotated (flags 32) at 90°: 20;
// diag, aligned (0, 0)-(3, 4): 5; angle, between the lines (0, 0)-(1, 0) and
// (0, 0)-(1, 1): 45; hole, diameter (10, 10)-(16, 18): 10; rad, radius: 2.5; ord,
// ordinate with flag 64: x = 7, ordy without it: y = 9; diag scaled by 2: 10; ord with
// origin [2, 0]: 5; the center lines (0, 0)-(10, 10) and (0, 10)-(10, 0) cross at
// [5, 5], [4, 3] from the origin [1, 2]; width on layer "other": 7. The square on
// layer "body" has no lone segment, and is what the file draws.
// expect echo: ECHO: 30, 20, 5, 45, 10, 2.5, 7, 9, 10, 5, [5, 5], [4, 3], 7
// expect volume: 16
f = "data/dims.dxf";
echo(dxf_dim(file = f, name = "width"), dxf_dim(file = f, name = "height"),
     dxf_dim(file = f, name = "diag"), dxf_dim(file = f, name = "angle"),
     dxf_dim(file = f, name = "hole"), dxf_dim(file = f, name = "rad"),
     dxf_dim(file = f, name = "ord"), dxf_dim(file = f, name = "ordy"),
     dxf_dim(file = f, name = "diag", scale = 2),
     dxf_dim(file = f, name = "ord", origin = [2, 0]),
     dxf_cross(file = f, layer = "center"), dxf_cross(file = f, layer = "center", origin = [1, 2]),
     dxf_dim(file = f, layer = "other", name = "width"));
linear_extrude(1) import(file = f, layer = "body");
