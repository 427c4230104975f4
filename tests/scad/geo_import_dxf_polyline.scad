// import() of DXF POLYLINE entities (their VERTEXes up to SEQEND; flag 70 bit 1
// closes them), one layer: the square 6 x 6 on layer "0"; the triangle on "other" is
// left out.
// expect volume: 36
// expect bbox: [0, 0, 0] [6, 6, 1]
// expect no-openscad: OpenSCAD 2021.01 skips POLYLINE entities with a warning
linear_extrude(1) import("data/polyline.dxf", layer = "0");
