// A 2-square plus a 1-square: a 3-square.
// expect volume: 9
linear_extrude(1) minkowski() { square(2); square(1); }
