// '*' removes a subtree, '%' keeps it out of the result.
// expect volume: 1
%cube(10);
cube(1);
*cube(5);
