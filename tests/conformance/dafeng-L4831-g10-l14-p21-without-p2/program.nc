O1001 (spec L4831: format 2 reads a timer that format 1's P2-P5 started; P21 of Z without P2 of Z is alarm 1152, nothing moves)
G98 G00 X20 Z10
G10 L14 P2 X80
G10 L14 P21 Z15 R100
G01 W-20 F100
M30
