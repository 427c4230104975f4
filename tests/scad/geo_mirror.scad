// A mirror keeps the volume positive (faces turned back out).
// expect volume: 6
// expect bbox: [-1, 0, 0] [0, 2, 3]
mirror([1, 0, 0]) cube([1, 2, 3]);
