// text() placement: HarfBuzz advances "l" by 30857 (1/64 px, / 1024 and * size / 100:
// 3.01337890625 at size 10), spacing multiplies it, halign = "center" moves the text
// back by half the total advance (2 * 1.5 * 3.01337890625 / 2 = 4.520068359375);
// valign = "center" moves it down by half the grid-fitted ascent (ceil(100634 / 64) * 64
// / 1024 * 0.1 = 9.83125, half 4.915625). Two rectangles 1.2205963134765625 wide and
// 10.063385009765625 high once on the 2^-16 grid (truncated toward zero).
// expect volume: 24.566661288030446
// expect bbox: [-3.584259033203125, -4.915618896484375, 0] [2.1563873291015625, 5.14776611328125, 1]
// expect counts: volumes=2
linear_extrude(1)
  text("ll", size = 10, font = "Liberation Sans", halign = "center", valign = "center",
       spacing = 1.5);
