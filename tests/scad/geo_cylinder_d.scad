// d and center: a unit-radius 4-gon prism of height 2 about the origin.
// expect volume: 4
// expect bbox: [-1, -1, -1] [1, 1, 1]
cylinder(h = 2, d = 2, center = true, $fn = 4);
