// import() of SVG paths with cubic (C) and quadratic (Q, T) curves, relative commands,
// on a page 40 x 30 pt (a bare number is a point, 25.4/72 mm; without a viewBox the
// coordinates are not scaled). Compared with OpenSCAD.
// expect valid
// expect counts: volumes=2
linear_extrude(1) import("data/curves.svg");
