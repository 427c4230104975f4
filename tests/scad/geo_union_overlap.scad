// 8 + 8 - 1.
// expect volume: 15
// expect counts: volumes=1
union() { cube(2); translate([1, 1, 1]) cube(2); }
