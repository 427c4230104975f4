// rotate(a, v) about the x axis: y goes to z.
// expect volume: 6
// expect bbox: [0, -3, 0] [1, 0, 2]
rotate(90, [1, 0, 0]) cube([1, 2, 3]);
