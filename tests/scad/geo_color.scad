// color() keeps the geometry.
// expect volume: 1
color("red") cube(1);
