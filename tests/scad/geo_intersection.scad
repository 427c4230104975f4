// expect volume: 1
// expect bbox: [1, 1, 1] [2, 2, 2]
intersection() { cube(2); translate([1, 1, 1]) cube(2); }
