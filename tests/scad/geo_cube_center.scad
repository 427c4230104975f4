// expect volume: 1000
// expect bbox: [-5, -5, -5] [5, 5, 5]
cube(10, center = true);
