// expect volume: 30
// expect bbox: [0, 0, 0] [2, 3, 5]
linear_extrude(5) square([2, 3]);
