// text(): the glyph "l" of Liberation Sans (fonts-liberation) is one rectangle. At
// OpenSCAD's fixed character size (100000/64 pt at 100 dpi) FreeType's hinted outline
// has x from 9358 to 21564 and y from 0 to 100634 (1/64 px); read / 1000, scaled by
// size / 100 and truncated to OpenSCAD's grid of 2^-16: x from 61328 / 65536 to
// 141321 / 65536, y from 0 to 659514 / 65536.
// expect volume: 12.283330644015223
// expect bbox: [0.935791015625, 0, 0] [2.1563873291015625, 10.063385009765625, 1]
// expect counts: faces=6 volumes=1
linear_extrude(1) text("l", size = 10, font = "Liberation Sans");
