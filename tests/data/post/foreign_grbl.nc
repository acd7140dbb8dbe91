; hand-written GRBL program (not from LeatherCut): a 40 x 30 mm rectangle
; with a 10 mm radius round corner, servo knife on M3/M5
G21 G90 G17 G94
M5
G0 X20 Y20
M3 S1000
G4 P0.25
G1 X50 Y20 F3000
G3 X60 Y30 I0 J10
G1 X60 Y50
G1 X20 Y50
G1 X20 Y20
M5
G0 X0 Y0
M2
