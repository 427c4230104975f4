// Two rectangles turned together with the whole profile's 4 segments.
// expect volume: 20
rotate_extrude($fn = 4) { translate([2, 0]) square(1); translate([2, 2]) square(1); }
