// A square hole through a 3-cube: 27 - 3.
// expect volume: 24
// expect area: 64
difference() { cube(3); translate([1, 1, -1]) cube([1, 1, 5]); }
