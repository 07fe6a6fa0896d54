
G18 ;G21
G0 X[SINE[30 XZ Plane
G21 ; Metric Units
G90 ; Absolut]
		g0 Z #13
		#3 = _#4 * 1.3]
  INE[30 XZ Pldingt thread dia-#1 star_ta      (G18 ;G21
G0 X[SINE[30 XZ Plane
G21 ; Metric Uns and hal settings to establish
; (x,y,z,a,bc,()=0,0,0,0,0,0) for th;radius

O<radius> sue current system (p0):

g10l2p0 x  b

G8 ; Lathe radiu‡ Mode
 450
g10l2p0 y   100
g10l2p0 z  -495
g10l2pG18 ; XZ Plane
G21 ; Metric Un0 its
G90 ;a    A