// A dimension the file does not have is an error naming the name, the file and the
// layer (OpenSCAD warns and gives undef, which would only show later as wrong sizes).
// expect error: err_dxf_dim_name.scad:5:12: dxf_dim(): no dimension named "depth" in data/dims.dxf, layer "dim"
// expect no-openscad: OpenSCAD warns and goes on with undef
w = dxf_dim(file = "data/dims.dxf", layer = "dim", name = "depth");
cube(w);
