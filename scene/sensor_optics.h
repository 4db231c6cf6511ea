// The camera's lens for rendered colour: depth of field (thin lens), MTF blur (a Gaussian PSF) and lateral
// chromatic aberration, applied to the linear colour before the sensor model (scene/sensor_model.h: distortion,
// vignetting, noise), as light passes the optics before it reaches the sensor. Depth, labels, normals and flow are
// never touched: the ground truth stays the ideal pinhole's, and the exact depth is what drives the defocus.
//
// In this order, each a pure function of its inputs (bitwise the same for any thread count):
// 1. Depth of field. Thin lens with focal length f = fx * pixel pitch, aperture diameter A = f / N (N = aperture_f)
//    and focus distance s: a point at planar depth d is imaged as a disc of diameter
//      c = A f |d - s| / (d (s - f))   on the sensor,  c / pitch pixels;   sky (d = +inf): A f / (s - f).
//    The disc's radius is capped at kMaxCocRadiusPx. The image is a gather of these discs: output pixel p sums
//    every source pixel q whose disc reaches p, weighted by the disc's coverage of p (its edge antialiased over one
//    pixel: clamp(reach - |p - q| + 0.5, 0, 1)) over the disc's area (max(pi r^2, 1)), normalised by the weights'
//    sum. Foreground / background rule: a source in front of p or at its depth (d_q <= d_p) reaches its own radius
//    r_q; a source behind p reaches only min(r_q, r_p). So a sharp surface at the focus distance takes no light from
//    a blurred background behind it (its edge does not bleed), while a blurred foreground spreads over what lies
//    behind it, as a real lens's partial occlusion does. A pixel no other source reaches keeps its value exactly.
// 2. MTF blur: a separable Gaussian PSF of standard deviation mtf_sigma_px, as Lindeberg's discrete Gaussian (the
//    kernel whose variance is exactly sigma^2 at any sigma; weights proportional to the modified Bessel function
//    I_n(sigma^2), summed from its power series with + * / only, so no libm call shapes the image), truncated at
//    ceil(4 sigma) + 1 taps a side and renormalised; edges clamp to the border pixel.
// 3. Lateral chromatic aberration: red and blue magnified about the principal point so that at the farthest image
//    corner red lies chromatic_aberration_px further out and blue as far further in (negative: the other way);
//    bilinear resampling, edges clamped. Green and alpha stay.
// Alpha (coverage) goes through 1 and 2 with the colour: the lens spreads coverage as it spreads light.
// With every optics key at 0 (or the sensor disabled) nothing is done at all: the image stays bitwise the same.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sward {

class JsonReader;
struct Intrinsics;
struct SensorParams;

// COST: the depth-of-field gather visits about pi (r + 0.5)^2 sources per pixel, r the largest circle of confusion
// near it (16 x 16 tiles): the cap bounds a frame's worst case (about 900 sources a pixel). One core, 640x480: 16 ms
// with radii below 0.7 px (f/1.4, 3.45 um pixels, focused at 0.6 m), 120 ms with radii of 5-6 px, 0.7 s with every
// radius at the cap; the MTF blur (sigma 0.7 px) 6.5 ms, the chromatic aberration 11 ms.
inline constexpr double kMaxCocRadiusPx = 16.0;

// The lens keys of `camera.sensor` (SensorParams::optics); every effect 0 = none.
struct LensOptics {
    double mtfSigmaPx = 0.0;            // Gaussian PSF standard deviation, pixels (0 .. 5)
    double apertureF = 0.0;             // f-number N; 0 = a pinhole, no depth of field (else 0.7 .. 64)
    double focusDistanceM = 0.0;        // s, metres; required with an aperture
    double pixelSizeUm = 3.45;          // pixel pitch: the focal length is fx * pitch
    double chromaticAberrationPx = 0.0; // lateral: red out, blue in by this much at the farthest corner (-10 .. 10)

    // True when any key asks for an effect (aperture, MTF or chromatic aberration).
    bool active() const { return apertureF > 0.0 || mtfSigmaPx > 0.0 || chromaticAberrationPx != 0.0; }
};

// Reads the lens keys of a sensor object ("mtf_sigma_px", "aperture_f", "focus_distance_m", "pixel_size_um",
// "chromatic_aberration_px"), range-checked, errors naming the key.
void parseLensOptics(JsonReader& reader, LensOptics& optics);
// Writes them into a sensor's JSON when active() (a scene without optics records what it recorded before).
void lensOpticsToJson(const LensOptics& optics, nlohmann::json& json);
// What the parser cannot check without the camera: the focus distance must exceed the focal length
// fx * pixel_size_um. Throws sward::Error naming the keys.
void checkOptics(const LensOptics& optics, const Intrinsics& intrinsics);

class SensorOptics {
public:
    // threads: for the passes (0 = every hardware thread); results do not depend on it. Nothing is done unless the
    // sensor is enabled and its optics active().
    SensorOptics(const SensorParams& params, const Intrinsics& intrinsics, uint32_t threads = 0);

    bool active() const { return active_; }
    // The circle of confusion's radius in pixels at planar depth `depth` metres (+inf or NaN: sky), not capped;
    // 0 without an aperture.
    double cocRadiusPx(double depth) const;
    // The MTF kernel's taps 0..radius (tap -k = tap k), summing to 1 over both sides; empty without MTF blur.
    const std::vector<float>& mtfKernel() const { return mtfKernel_; }

    // `rgba`: width*height*4 linear floats, top row first; `depth` (width*height planar metres, +inf = sky) is the
    // same view's exact depth. Replaced by the image through the lens.
    void apply(std::span<const float> depth, std::span<float> rgba) const;
    // Same on half bit patterns (FrameImages::rgbaHalf), rounded to nearest even; nothing converted when inactive.
    void applyHalf(std::span<const float> depth, std::span<uint16_t> rgbaHalf) const;

private:
    void depthOfField(std::span<const float> depth, std::span<float> rgba) const;
    void mtfBlur(std::span<float> rgba) const;
    void chromaticAberration(std::span<float> rgba) const;

    bool active_ = false;
    uint32_t width_ = 0, height_ = 0, threads_ = 0;
    double cx_ = 0.0, cy_ = 0.0;
    double focusM_ = 0.0;            // s
    double cocRadiusAtInfinity_ = 0; // A f / ((s - f) pitch) / 2 pixels: the radius is this times |1 - s / d|
    std::vector<float> mtfKernel_;
    double redScale_ = 1.0, blueScale_ = 1.0; // chromatic aberration's magnifications
};

} // namespace sward
