// S1's ice shell (R 1, n 1.31; water core R 0.7, n 1.33) on an analytic checker floor, lit by a
// sphere area light of radius 0.3 at (1.5, 4, -6), behind the shell as seen from the camera, so that the caustic falls towards the camera: the POV-Ray 3.7 side of the caustics comparison
// (bench/render/compare_povray_caustics.sh), the same scene as data/scenes/s1_caustics_area.toml.
// Photons (refraction and reflection through both dielectrics), a circular area light oriented to
// each shaded point (a sphere seen from afar is a disc), adaptive anti-aliasing from the command
// line (+A +AM2 +R). Quality knobs, declared on the command line (Declare=NAME=VALUE):
//   PHOTONS     photons shot (global count), default 200000
//   AREA_N      area light samples per side (N x N, adaptive 1), default 5
// Light units: thaw's sphere light of intensity I gives E = I / d^2 at distance d; POV-Ray's
// fade_power 2 gives 2 C / (1 + (d / fade_distance)^2), which is 2 C fade_distance^2 / d^2 to 1e-4
// relative for d > 1 when fade_distance = 0.01: C = I / (2 fade_distance^2) = 55 / 2e-4.
#version 3.7;
#ifndef (PHOTONS) #declare PHOTONS = 200000; #end
#ifndef (AREA_N) #declare AREA_N = 5; #end
global_settings {
  assumed_gamma 1.0
  max_trace_level 10
  ambient_light rgb <0.1, 0.1, 0.1>
  photons { count PHOTONS autostop 0 jitter 0.4 max_trace_level 10 }
}
background { color rgb <0.25, 0.3, 0.4> }
camera { perspective location <0, 1.3, 5.5> sky <0, 1, 0> up y right -x*1 direction z angle 35.000000 look_at <0, -0.5, 0.6> }
light_source {
  <1.5, 4, -6> color rgb 275000 * <1, 1, 1>
  fade_distance 0.01 fade_power 2
  area_light <0.6, 0, 0>, <0, 0, 0.6>, AREA_N, AREA_N adaptive 1 jitter circular orient
  photons { refraction on reflection on area_light }
  // thaw's sphere light is visible (radiance I / (pi r^2) = 55 / (pi 0.09) = 194.5) and shows in
  // the shell's reflection: so does this one
  looks_like { sphere { <0, 0, 0>, 0.3 pigment { color rgb 194.5 } finish { emission 1 ambient 0 diffuse 0 } } }
}
#declare Clear = texture { pigment { color rgbf <1,1,1,1> } finish { ambient 0 diffuse 0 specular 0 reflection { 0, 1 fresnel on } conserve_energy } }
difference { sphere { <0, 0, 0>, 1 } sphere { <0, 0, 0>, 0.7 } texture { Clear } interior { ior 1.31 }
  photons { target refraction on reflection on } }
sphere { <0, 0, 0>, 0.7014 texture { Clear } interior { ior 1.33 } photons { target refraction on reflection on } }
plane { y, -1 texture { pigment { checker color rgb <0.9, 0.9, 0.9>, color rgb <0.6, 0.08, 0.08> scale 0.5 translate <0, 0.25, 0> } finish { ambient 1 diffuse 1 specular 0 } } }
