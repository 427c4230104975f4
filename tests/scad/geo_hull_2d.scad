// expect volume: 4
linear_extrude(1) hull() { square(1); translate([3, 0]) square(1); }
