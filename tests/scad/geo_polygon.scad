// A right triangle of legs 4 and 3, extruded 2.
// expect volume: 12
linear_extrude(2) polygon([[0, 0], [4, 0], [0, 3]]);
