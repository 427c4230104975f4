// A shear keeps the volume.
// expect volume: 1
// expect bbox: [0, 0, 0] [2, 1, 1]
multmatrix([[1, 1, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) cube(1);
