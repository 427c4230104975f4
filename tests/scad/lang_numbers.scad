// Number text as OpenSCAD prints it: 6 significant digits, exponent below -5 or from 6 up.
// expect echo: ECHO: 0.333333, 1e+10, 1.23457e+8, 0.00001, 1.5e-7, 1e+6, 999999, 100000, 0, -2.5
echo(1 / 3, 1e10, 123456789, 0.00001, 1.5e-7, 1e6, 999999, 100000, -0, -2.5);
