// version() of the OpenSCAD language cellforge reads.
// expect echo: ECHO: [2021, 1, 0], 2.02101e+7
echo(version(), version_num());
