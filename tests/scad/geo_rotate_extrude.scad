// A square annulus: outer 4-gon of circumradius 3 (area 18), inner of 2 (area 8).
// expect volume: 10
rotate_extrude($fn = 4) translate([2, 0]) square(1);
