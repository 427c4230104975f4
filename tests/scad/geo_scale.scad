// expect volume: 24
// expect bbox: [0, 0, 0] [2, 3, 4]
scale([2, 3, 4]) cube(1);
