// 90 degrees in 2 segments of 45: (1/2) sin(45) (4 - 1) per segment, height 2.
// expect volume: 4.242640687119285
rotate_extrude(angle = 90, $fn = 8) translate([1, 0]) square([1, 2]);
