// rotate([0, 0, 90]) after translate: the box lands at x in [-2, 0], y in [1, 3].
// expect volume: 8
// expect bbox: [-2, 1, 0] [0, 3, 2]
rotate([0, 0, 90]) translate([1, 0, 0]) cube(2);
