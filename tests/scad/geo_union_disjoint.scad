// Two separate boxes: two cells.
// expect volume: 16
// expect counts: volumes=2
cube(2);
translate([5, 0, 0]) cube(2);
