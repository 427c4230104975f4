// import() of SVG (100 x 50 mm, viewBox 100 x 50: one unit a millimetre, y turned up):
// a rect 10 x 20; a path of two squares 20 and 10, filled even-odd (300); a circle of
// radius 5 in 40 segments (20 r^2 sin 9 degrees); in a group translated and scaled by 2
// a triangle of legs 5 (50); two overlapping 10 x 10 rects, united (150). The rect in
// <defs> is not drawn.
// expect volume: 778.217232520115
// expect bbox: [0, 10, 0] [70, 50, 1]
// expect counts: volumes=5
linear_extrude(1) import("data/shapes.svg");
