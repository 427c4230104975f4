// The section of a box by z = 0: a 3 x 2 rectangle.
// expect volume: 6
// expect bbox: [0, 0, 0] [3, 2, 1]
linear_extrude(1) projection(cut = true) translate([0, 0, -1]) cube([3, 2, 2]);
