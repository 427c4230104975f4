// An unknown variable is undef with a warning, as OpenSCAD does.
// expect echo: ECHO: undef
// expect warning: unknown variable 'nope'
echo(nope);
