%
O2001 (a subprogram from the program store: a step out and back along X)
G01 U10. F600
U-10.
M99
%
