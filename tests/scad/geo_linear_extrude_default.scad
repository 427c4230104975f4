// linear_extrude's default height is 100.
// expect volume: 100
// expect bbox: [0, 0, 0] [1, 1, 100]
linear_extrude() square(1);
