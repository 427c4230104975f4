// surface(center = true) of heights 0 -2 / 1 3: the bottom at -3, one cell of mean 0.5,
// volume 3.5, centred in x and y.
// expect volume: 3.5
// expect bbox: [-0.5, -0.5, -3] [0.5, 0.5, 3]
surface(file = "data/heights_negative.dat", center = true, convexity = 2);
