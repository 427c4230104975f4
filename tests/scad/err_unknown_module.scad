// An unknown module is a warning and makes nothing.
// expect warning: unknown module 'foo'
// expect volume: 1
foo();
cube(1);
