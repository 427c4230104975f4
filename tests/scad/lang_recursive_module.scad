// A recursive module: a staircase of 4 unit cubes, each touching the next along an edge
// only, so each is a cell of its own.
// expect volume: 4
// expect counts: volumes=4
module stairs(n) if (n > 0) { translate([n - 1, 0, n - 1]) cube(1); stairs(n - 1); }
stairs(4);
