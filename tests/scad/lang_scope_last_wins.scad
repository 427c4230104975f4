// The last assignment in a scope wins, evaluated where the first one stands.
// expect echo: ECHO: 2
// expect warning: 'a' was assigned on line 4
a = 1;
echo(a);
a = 2;
