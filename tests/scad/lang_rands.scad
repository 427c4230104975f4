// rands() with a seed gives OpenSCAD's numbers (std::mt19937).
// expect echo: ECHO: [0.796543, 0.183435], true
r = rands(0, 1, 2, 42);
echo(r, rands(5, 6, 3, 7) == rands(5, 6, 3, 7));
