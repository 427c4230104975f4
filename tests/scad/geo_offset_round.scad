// offset(r) with round joins: the box grows by 1 on every side.
// expect bbox: [-1, -1, 0] [3, 3, 1]
// expect valid
linear_extrude(1) offset(r = 1, $fn = 16) square(2);
