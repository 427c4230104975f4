// A tetrahedron, faces clockwise seen from outside: volume 1/6.
// expect volume: 0.16666666666666666
// expect counts: vertices=4 faces=4
polyhedron(points = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
           faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]);
