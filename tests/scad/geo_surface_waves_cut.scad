// projection(cut = true) of a 20 x 20 surface() of waves (data/waves.dat) at height 55:
// the section crosses slanted faces all over the grid. Its area, clipped triangle by
// triangle from the same four-triangles-per-cell surface by an independent script
// (Python, in doubles): 136.99512971611563.
// expect volume: 136.99512971611563
// expect valid
linear_extrude(1) projection(cut = true) translate([0, 0, -55]) surface("data/waves.dat");
