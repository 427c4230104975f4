// surface() of a 2 x 2 grey PNG (top row 0 255, bottom row 51 102): heights are 100/255
// of the grey level, the image's top row at y = 1: 0 100 / 20 40, the bottom at -1;
// volume mean + 1 = 41.
// expect volume: 41
// expect bbox: [0, 0, -1] [1, 1, 100]
surface("data/heights.png");
