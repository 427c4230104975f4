// Box plus box: a 3-cube.
// expect volume: 27
minkowski() { cube(2); cube(1); }
