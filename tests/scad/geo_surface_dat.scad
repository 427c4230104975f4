// surface() of a .dat heightmap: each cell is four triangles about its centre (at the
// mean height), so the volume over a cell is the mean of its corners; the bottom is
// one below the lowest height, or 0. Cells (1 2 4 9) and (2 3 9 6): 4 + 5.
// expect volume: 9
// expect bbox: [0, 0, 0] [2, 1, 9]
surface("data/heights.dat");
