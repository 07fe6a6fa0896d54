%
O0004
(Seed 004, Fig. 10 with the omitted layers restored: the importer case study.)
(Transcribed from samples/gcode/seed004_fig10.nc, itself shared/SEEDS-SPEC.md 4.2.5 L1-L76.)
(Repairs: roughing layers 2-5 restored from the comment at L24, 5 layers of 5.9, each)
(as layer 1: a helix on R7.2 about X70 Y55 from where layer 1 ends, the same rings.)
(Finishing layers 2-6 restored from the comment at L49, 6 layers to Z-30: Z-10 to Z-30,)
(5 apart; layer 1 keeps the printed Z-2. Each as layer 1, closing its outer ring at X70 Y101)
(as layer 1 does, so L74 is layer 6's last corner and L75 lifts from X70.)
(Without these layers the roughing leaves 24.1 mm of floor, not the 0.5 the paper states.)
G54 G90 G21 G40 G49 M5 M9
G0 Z100. (Move to the secure plane)
(To drill and ream a thru hole)
T2 M6 (Use a spiral drill, diameter 20mm)
G43 H2 (Length compensation by 70mm)
M8 M3 F900. S720
G0 Z30.
G90 G99 G81 X20. Y60. Z-18. R10.
G99 G81 X20. Y60. Z-36. R10. F1800.
G99 G81 X20. Y60. Z-60. R10. F1350.
G1 Z10. F1800.
G80 G49 M5 M9 (end of drilling cycle)
T3 M6 (Use a reamer, diameter 22mm)
G43 H3 (Length compensation by 50mm)
M8 M3 S1080
G90 G99 G85 X20. Y60. Z-60. R10.
G80 G49 M5 M9 (End of reaming cycle)
(To cut a pocket, rough & finish)
T1 M6 (Use an endmill, diameter 18mm)
G43 H1 (Length compensation by 50mm)
M8 S1200 M3 F2400.
G0 Z30.
X64.754 Y50.069 Z15.
(To rough pocket in 5 layers, 5.9/layer)
(First 2 blocks: to run helical approach)
G2 X77.2 Y55. Z-5.9 I5.246 J4.932
G2 X70. Y55. I-3.60 J0.
G1 Y90.
X75.
Y50.
X65.
Y90.
X70.
Y95.
X80.
Y45.
X60.
Y95.
X70.
Y100.
X85.
Y40.
X55.
Y100.
X70.
Z0.
G0 X69.532 Y47.815 (End of 1st layer)
G2 X77.2 Y55. Z-11.8 I.468 J7.185 (rough layer 2)
G2 X70. Y55. I-3.60 J0.
G1 Y90.
X75.
Y50.
X65.
Y90.
X70.
Y95.
X80.
Y45.
X60.
Y95.
X70.
Y100.
X85.
Y40.
X55.
Y100.
X70.
Z0.
G0 X69.532 Y47.815
G2 X77.2 Y55. Z-17.7 I.468 J7.185 (rough layer 3)
G2 X70. Y55. I-3.60 J0.
G1 Y90.
X75.
Y50.
X65.
Y90.
X70.
Y95.
X80.
Y45.
X60.
Y95.
X70.
Y100.
X85.
Y40.
X55.
Y100.
X70.
Z0.
G0 X69.532 Y47.815
G2 X77.2 Y55. Z-23.6 I.468 J7.185 (rough layer 4)
G2 X70. Y55. I-3.60 J0.
G1 Y90.
X75.
Y50.
X65.
Y90.
X70.
Y95.
X80.
Y45.
X60.
Y95.
X70.
Y100.
X85.
Y40.
X55.
Y100.
X70.
Z0.
G0 X69.532 Y47.815
G2 X77.2 Y55. Z-29.5 I.468 J7.185 (rough layer 5)
G2 X70. Y55. I-3.60 J0.
G1 Y90.
X75.
Y50.
X65.
Y90.
X70.
Y95.
X80.
Y45.
X60.
Y95.
X70.
Y100.
X85.
Y40.
X55.
Y100.
X70.
Z0.
G0 X69.532 Y47.815
(Layers 2-5 above: restored)
(To finish pocket in 6 layers. 5mm/layer)
(Bottom allowance 0.5, side allowance 1)
G0 Z30.
X74.890 Y60.285 Z15.
(First 2 blocks: to run helical approach)
G2 X77.2 Y55. Z-2. I-4.891 J-5.285
G2 X70. Y55. I-3.60 J0.
G1 Y93.
X78.
Y47.
X62.
Y93.
X70.
Y101.
X85.
G2 X86. Y100. I0. J-1.
G1 Y40.
G2 X85. Y39. I-1. J0.
G1 X55.
G2 X54. Y40. I0. J1.
G1 Y100.
G2 X55. Y101. I1. J0.
G1 X70.
Z0. (End of 1st layer)
G0 X74.890 Y60.285
G2 X77.2 Y55. Z-10. I-4.891 J-5.285 (finish layer 2)
G2 X70. Y55. I-3.60 J0.
G1 Y93.
X78.
Y47.
X62.
Y93.
X70.
Y101.
X85.
G2 X86. Y100. I0. J-1.
G1 Y40.
G2 X85. Y39. I-1. J0.
G1 X55.
G2 X54. Y40. I0. J1.
G1 Y100.
G2 X55. Y101. I1. J0.
G1 X70.
Z0.
G0 X74.890 Y60.285
G2 X77.2 Y55. Z-15. I-4.891 J-5.285 (finish layer 3)
G2 X70. Y55. I-3.60 J0.
G1 Y93.
X78.
Y47.
X62.
Y93.
X70.
Y101.
X85.
G2 X86. Y100. I0. J-1.
G1 Y40.
G2 X85. Y39. I-1. J0.
G1 X55.
G2 X54. Y40. I0. J1.
G1 Y100.
G2 X55. Y101. I1. J0.
G1 X70.
Z0.
G0 X74.890 Y60.285
G2 X77.2 Y55. Z-20. I-4.891 J-5.285 (finish layer 4)
G2 X70. Y55. I-3.60 J0.
G1 Y93.
X78.
Y47.
X62.
Y93.
X70.
Y101.
X85.
G2 X86. Y100. I0. J-1.
G1 Y40.
G2 X85. Y39. I-1. J0.
G1 X55.
G2 X54. Y40. I0. J1.
G1 Y100.
G2 X55. Y101. I1. J0.
G1 X70.
Z0.
G0 X74.890 Y60.285
G2 X77.2 Y55. Z-25. I-4.891 J-5.285 (finish layer 5)
G2 X70. Y55. I-3.60 J0.
G1 Y93.
X78.
Y47.
X62.
Y93.
X70.
Y101.
X85.
G2 X86. Y100. I0. J-1.
G1 Y40.
G2 X85. Y39. I-1. J0.
G1 X55.
G2 X54. Y40. I0. J1.
G1 Y100.
G2 X55. Y101. I1. J0.
G1 X70.
Z0.
G0 X74.890 Y60.285
G2 X77.2 Y55. Z-30. I-4.891 J-5.285 (finish layer 6)
G2 X70. Y55. I-3.60 J0.
G1 Y93.
X78.
Y47.
X62.
Y93.
X70.
Y101.
X85.
G2 X86. Y100. I0. J-1.
G1 Y40.
G2 X85. Y39. I-1. J0.
G1 X55.
G2 X54. Y40. I0. J1.
G1 Y100.
G2 X55. Y101. I1. J0.
G1 X70. (REPAIR: closes layer 6 as layer 1 closes; from X55 the printed L75 ramp leaves 0.5 under the wall)
(Layers 2-6 above: restored)
G1 X70. Z15. (End of finishing)
M30
%
