// offset(delta) with mitred corners: 2-square grows to a 4-square.
// expect volume: 16
linear_extrude(1) offset(delta = 1) square(2);
