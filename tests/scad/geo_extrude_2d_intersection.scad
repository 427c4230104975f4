// expect volume: 1
linear_extrude(1) intersection() { square(2); translate([1, 1]) square(2); }
