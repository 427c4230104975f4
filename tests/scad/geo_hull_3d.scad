// The hull of two unit cubes 3 apart: a 4 x 1 x 1 box.
// expect volume: 4
hull() { cube(1); translate([3, 0, 0]) cube(1); }
