// A 4-square with a 2-square hole: 16 - 4.
// expect volume: 12
// expect area: 48
linear_extrude(1) difference() { square(4); translate([1, 1]) square(2); }
