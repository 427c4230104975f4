// surface(invert = true) of the same PNG: OpenSCAD 2021.01 maps a grey level g to
// 100/255 (1 - g); mean 100/255 (1 - 102), bottom 100/255 (1 - 255) - 1, so the volume
// is 100/255 (255 - 102) + 1 = 61.
// expect volume: 61
surface("data/heights.png", invert = true);
