// The procedural plant painters of the built-in atlas: grass clumps, ferns over leaf litter, flowers and shrubs.
//
// Colours are albedos in linear RGB, not picked by eye. Sources: leaf and grass reflectance spectra of the
// ECOSTRESS / ASTER spectral library (Baldridge et al. 2009, Meerdink et al. 2019: green grass, dry grass, leaf
// litter) and the LOPEX93 leaf set (Hosgood et al. 1994), band-averaged over the sRGB primaries: a live green
// leaf reflects about 0.05-0.09 red, 0.09-0.14 green, 0.03-0.05 blue (chlorophyll absorbs red and blue, the
// green peak is only 10-15 %); dry straw 0.30-0.40, 0.26-0.34, 0.14-0.20; dead brown leaves 0.12-0.18,
// 0.09-0.12, 0.05-0.07. White petals reflect about 0.6-0.7 (never 1), yellow ones (0.55, 0.42, 0.05). Real
// meadows measured by sward-eval look (issue 47) have a vegetation saturation of 0.16 [0.13-0.22] and a value
// std of 0.11: desaturated greens mixed with dry and dead blades, which the palettes below follow.
#include "vegetation/atlas_paint.h"

#include <array>

namespace sward::atlas_detail {

namespace {

// ---- grass -----------------------------------------------------------------------------------------------------

// Live greens run from a bluish shade leaf to a yellowish sunlit one; blue stays low (chlorophyll and carotenoids
// absorb it), so the sky's blue fill light does not turn the meadow grey-teal.
const vec3 kLiveGreens[] = {albedo(0.062f, 0.110f, 0.032f), albedo(0.080f, 0.122f, 0.034f),
                            albedo(0.056f, 0.096f, 0.036f), albedo(0.090f, 0.130f, 0.038f)};
const vec3 kStraw = albedo(0.30f, 0.26f, 0.15f);      // dry blade
const vec3 kYellowed = albedo(0.20f, 0.19f, 0.08f);   // senescing blade, chlorophyll going
const vec3 kDeadBrown = albedo(0.15f, 0.105f, 0.06f); // dead blade or leaf

// Shares of a clump's blades (per variant, then jittered): every variant carries some dry, yellowed and dead
// material, as every real tuft does; alternate variants are drier.
struct GrassMix {
    float dry, yellowed, dead;
};

GrassMix grassMix(Dice& dice, uint32_t variant) {
    static constexpr float kDry[] = {0.08f, 0.22f, 0.12f, 0.35f, 0.06f, 0.18f};
    const float dry = kDry[variant % 6] + dice.range(0.0f, 0.08f);
    return {dry, dice.range(0.10f, 0.22f), dice.range(0.04f, 0.10f)};
}

// One blade's base and tip colour: live blades vary in hue (bluish to yellowish green) and value, every blade is
// lighter toward its tip (thinner tissue, sky seen through it), dry and dead ones are straw or brown.
void colourBlade(Stroke& s, Dice& dice, const GrassMix& mix) {
    const float state = dice();
    const vec3 green = dice.jitter(glm::mix(kLiveGreens[dice.pick(4)], kLiveGreens[dice.pick(4)], dice()), 0.18f);
    if (state < mix.dead) {
        s.base = dice.jitter(kDeadBrown, 0.15f);
        s.tip = dice.jitter(glm::mix(kDeadBrown, kStraw, 0.4f), 0.1f);
        s.tipStart = dice.range(0.2f, 0.5f);
    } else if (state < mix.dead + mix.dry) {
        s.base = glm::mix(green, kYellowed, dice.range(0.3f, 0.8f));
        s.tip = dice.jitter(kStraw, 0.15f);
        s.tipStart = dice.range(0.15f, 0.45f);
    } else if (state < mix.dead + mix.dry + mix.yellowed) {
        s.base = green;
        s.tip = dice.jitter(glm::mix(kYellowed, kStraw, dice.range(0.0f, 0.6f)), 0.1f);
        s.tipStart = dice.range(0.45f, 0.75f);
    } else {
        s.base = green;
        s.tip = glm::mix(green * 1.35f, kYellowed, dice.range(0.05f, 0.25f));
        s.tipStart = dice.range(0.35f, 0.7f);
    }
}

// The centreline of one blade: a curved, tapering arc; a few are bent over (folded at a kink) or broken off short.
struct BladeShape {
    std::vector<vec2> points;
    bool broken = false;
};

BladeShape bladeCentreline(Dice& dice, vec2 base, float lean, float bend, float length) {
    BladeShape shape;
    const float kind = dice();
    if (kind < 0.12f) { // bent over: the blade folds at 45-75 % of its length and hangs down
        const float kink = dice.range(0.45f, 0.75f);
        const vec2 p1 = base + direction(lean) * length * kink * 0.5f;
        const vec2 p2 = p1 + direction(lean + bend * 0.3f) * length * kink * 0.5f;
        shape.points = cubicBezier(base, p1, glm::mix(p1, p2, 0.7f), p2, 11);
        const float side = lean + bend >= 0.0f ? 1.0f : -1.0f;
        const vec2 d = direction(lean + side * dice.range(1.6f, 2.4f));
        const float rest = length * (1.0f - kink);
        for (int i = 1; i <= 5; ++i) shape.points.push_back(p2 + d * (rest * float(i) / 5.0f));
        return shape;
    }
    const bool broken = kind < 0.22f; // broken or grazed: a blunt end at 40-70 % of the length
    const float reach = broken ? dice.range(0.4f, 0.7f) : 1.0f;
    const vec2 p1 = base + direction(lean) * length * 0.35f * reach;
    const vec2 p2 = p1 + direction(lean + bend * 0.5f) * length * 0.35f * reach;
    const vec2 p3 = p2 + direction(lean + bend) * length * 0.32f * reach;
    shape.points = cubicBezier(base, p1, p2, p3, 16);
    shape.broken = broken;
    return shape;
}

void paintDeadLeaves(Plant& plant, Dice& dice, float S, int count, float spread) {
    for (int i = 0; i < count; ++i) {
        const vec2 at(S * 0.5f + dice.centred() * spread, S * (1.0f - dice.range(0.01f, 0.07f)));
        const float length = S * dice.range(0.035f, 0.07f);
        const vec2 dir = direction(kPi * 0.5f + dice.range(-0.6f, 0.6f)) * (dice() < 0.5f ? 1.0f : -1.0f);
        const vec3 c = dice.jitter(kDeadBrown, 0.2f);
        plant.push_back(leaf(at - dir * (length * 0.5f), dir, length, length * 0.22f, 0.0f, c, c * 1.1f));
    }
}

void paintSeedHeads(Plant& plant, Dice& dice, float S, uint32_t variant, float spread, float heightScale) {
    const vec2 root(S * 0.5f, S);
    const vec3 husk = variant % 2 == 0 ? albedo(0.26f, 0.22f, 0.12f) : albedo(0.17f, 0.12f, 0.10f);
    const int stems = 1 + int(dice() * 3.0f);
    for (int k = 0; k < stems; ++k) {
        const vec2 base = root + vec2(dice.centred() * spread * 0.6f, 0.0f);
        const float lean = dice.range(-0.3f, 0.3f), length = S * heightScale * dice.range(0.8f, 0.98f);
        const vec2 p3 = base + direction(lean + dice.range(-0.15f, 0.15f)) * length;
        const auto points =
            cubicBezier(base, base + direction(lean) * length * 0.4f, base + direction(lean) * length * 0.75f, p3, 14);
        plant.push_back({.points = points,
                         .halfWidths = widths(14, S * 0.003f, [](float t) { return 1.0f - 0.5f * t; }),
                         .base = albedo(0.07f, 0.10f, 0.04f),
                         .tip = albedo(0.20f, 0.18f, 0.10f),
                         .tipStart = 0.4f,
                         .shadeBase = 0.3f});
        // Spikelets alternate along the top third, pointing upwards, smaller towards the tip.
        const int spikelets = 9 + int(dice() * 6.0f);
        for (int i = 0; i < spikelets; ++i) {
            const float t = 0.68f + 0.32f * float(i) / float(spikelets - 1);
            const auto [at, tangent] = alongPolyline(points, t);
            const float side = i % 2 == 0 ? 1.0f : -1.0f, size = S * 0.03f * (1.1f - 0.5f * (t - 0.68f) / 0.32f);
            plant.push_back(leaf(at, rotate(tangent, side * dice.range(0.3f, 0.6f)), size, size * 0.26f, 0.0f,
                                 dice.jitter(husk, 0.12f), dice.jitter(husk * 1.15f, 0.1f)));
        }
    }
}

// ---- ferns and forest floor ------------------------------------------------------------------------------------

// Fern pinnae: darker, bluer green than grass (shade leaves), young tips lighter and yellower.
const vec3 kFernOld = albedo(0.042f, 0.080f, 0.026f), kFernYoung = albedo(0.090f, 0.135f, 0.038f);

// A fern variant's habit: how many fronds, how tall, how far they arch over, how wide the pinnae stand.
struct FernHabit {
    int fronds;
    float height, arch, pinnaAngle, pinnaLength, fan;
    int pairs;
};

FernHabit fernHabit(Dice& dice, uint32_t variant) {
    static constexpr int kFronds[] = {6, 4, 8, 5, 9, 3, 7, 5};
    return {.fronds = kFronds[variant % 8] + int(dice() * 2.0f),
            .height = dice.range(0.6f, 1.0f),
            .arch = dice.range(0.15f, 0.9f),
            .pinnaAngle = dice.range(0.85f, 1.35f),
            .pinnaLength = dice.range(0.17f, 0.27f),
            .fan = dice.range(0.45f, 0.8f),
            .pairs = 13 + int(dice() * 9.0f)};
}

void paintFrond(Plant& plant, Dice& dice, float S, const FernHabit& habit, float a) {
    const vec2 root(S * 0.5f, S);
    const float length = S * habit.height * dice.range(0.7f, 1.0f) * (1.0f - 0.25f * std::abs(a));
    const float droop = (a >= 0.0f ? 1.0f : -1.0f) * habit.arch * dice.range(0.6f, 1.2f);
    const vec2 base = root + vec2(dice.centred() * S * 0.03f, 0.0f);
    const vec2 p1 = base + direction(a * 0.7f) * length * 0.4f;
    const vec2 p2 = p1 + direction(a + droop * 0.4f) * length * 0.35f;
    const vec2 p3 = p2 + direction(a + droop) * length * 0.3f;
    const auto rachis = cubicBezier(base, p1, p2, p3, 24);
    const vec3 old = dice.jitter(kFernOld, 0.15f), young = dice.jitter(kFernYoung, 0.15f);

    // Pinnae in pairs, longest a third of the way up, shorter towards the tip; each droops a little and has
    // lobed edges (the half-width ripples) so it reads as a leaflet with pinnules.
    for (int j = 0; j < habit.pairs; ++j) {
        const float t = 0.14f + 0.84f * float(j) / float(habit.pairs - 1);
        const auto [at, tangent] = alongPolyline(rachis, t);
        const float profile = t < 0.3f ? 0.65f + 0.35f * t / 0.3f : 1.0f - 0.85f * (t - 0.3f) / 0.7f;
        const float plen = length * habit.pinnaLength * profile;
        for (float side : {-1.0f, 1.0f}) {
            const vec2 dir = rotate(tangent, side * habit.pinnaAngle * dice.range(0.9f, 1.1f));
            const vec3 c = dice.jitter(glm::mix(old, young, t * 0.8f), 0.08f);
            Stroke s{.base = c * 0.9f, .tip = c * 1.12f, .tipStart = 0.2f, .shadeBase = 0.2f, .midrib = 0.04f};
            for (int i = 0; i < 10; ++i) {
                const float u = float(i) / 9.0f;
                s.points.push_back(at + dir * (plen * u) + vec2(0.0f, 0.25f * plen * u * u));
                const float lobes = 0.72f + 0.28f * std::abs(std::cos(u * kPi * 4.5f));
                s.halfWidths.push_back(plen * 0.17f *
                                       std::pow(std::sin(kPi * std::min(u * 1.05f + 0.04f, 1.0f)), 0.55f) * lobes);
            }
            plant.push_back(std::move(s));
        }
    }
    plant.push_back({.points = rachis,
                     .halfWidths = widths(24, S * 0.004f, [](float t) { return 1.0f - 0.6f * t; }),
                     .base = albedo(0.06f, 0.08f, 0.035f),
                     .tip = young,
                     .tipStart = 0.3f,
                     .shadeBase = 0.25f});
}

// ---- flowers and shrubs ----------------------------------------------------------------------------------------

const vec3 kLeafGreens[] = {albedo(0.052f, 0.095f, 0.030f), albedo(0.072f, 0.115f, 0.034f),
                            albedo(0.047f, 0.085f, 0.030f)};

enum class FlowerForm { Daisy, Spike, Cup, Shrub };

struct FlowerStyle {
    FlowerForm form;
    vec3 petals; // linear albedo
    vec3 centre;
};

// Cycles through the four forms so that any variant count shows all of them, and through flower colours so each
// row has yellow, white, purple and red heads. Petal albedos: white ~0.62, yellow (0.55, 0.42, 0.05), the
// saturated reds and blues of real petals reflect well under half of the light of their own colour.
FlowerStyle flowerStyle(uint32_t variant, Dice& dice) {
    static const FlowerForm kForms[] = {FlowerForm::Daisy, FlowerForm::Spike, FlowerForm::Cup, FlowerForm::Shrub};
    static const std::array<vec3, 8> kColours = {albedo(0.55f, 0.42f, 0.05f),  albedo(0.20f, 0.11f, 0.30f),
                                                 albedo(0.40f, 0.07f, 0.045f), albedo(0.60f, 0.60f, 0.55f),
                                                 albedo(0.64f, 0.63f, 0.58f),  albedo(0.13f, 0.15f, 0.36f),
                                                 albedo(0.56f, 0.25f, 0.04f),  albedo(0.50f, 0.25f, 0.30f)};
    static const std::array<vec3, 8> kCentres = {albedo(0.30f, 0.15f, 0.02f), albedo(0.20f, 0.11f, 0.30f),
                                                 albedo(0.03f, 0.03f, 0.02f), albedo(0.50f, 0.38f, 0.06f),
                                                 albedo(0.52f, 0.36f, 0.04f), albedo(0.13f, 0.15f, 0.36f),
                                                 albedo(0.10f, 0.05f, 0.02f), albedo(0.50f, 0.40f, 0.10f)};
    const size_t c = variant % 8;
    // Beyond the first eight, colours are shifted a little so repeated styles are not identical.
    const float shift = variant >= 8 ? dice.range(0.85f, 1.1f) : 1.0f;
    return {kForms[variant % 4], glm::clamp(kColours[c] * shift, 0.0f, 1.0f), kCentres[c]};
}

void paintRosette(Plant& plant, Dice& dice, float S, int count) {
    for (int i = 0; i < count; ++i) {
        const float a = dice.range(-1.3f, 1.3f);
        const float length = S * dice.range(0.18f, 0.34f) * (1.0f - 0.3f * std::abs(a));
        const vec3 c = dice.jitter(kLeafGreens[dice.pick(3)], 0.15f);
        Stroke s = leaf(vec2(S * 0.5f + dice.centred() * S * 0.04f, S), direction(a), length,
                        S * dice.range(0.024f, 0.038f), 0.25f, c * 0.9f, c * 1.15f);
        s.shadeBase = 0.3f;
        plant.push_back(std::move(s));
    }
}

// A slightly curved stem with a few leaves; returns its centreline so a flower head can be put on top.
std::vector<vec2> paintStem(Plant& plant, Dice& dice, float S, float height) {
    const vec2 base(S * 0.5f + dice.centred() * S * 0.07f, S);
    const float lean = dice.range(-0.35f, 0.35f), curve = dice.range(-0.25f, 0.25f);
    const auto points =
        cubicBezier(base, base + direction(lean * 0.5f) * height * 0.35f, base + direction(lean) * height * 0.7f,
                    base + direction(lean + curve) * height, 16);
    const vec3 green = dice.jitter(albedo(0.065f, 0.11f, 0.04f), 0.12f);
    plant.push_back({.points = points,
                     .halfWidths = widths(16, S * 0.0042f, [](float t) { return 1.0f - 0.4f * t; }),
                     .base = green * 0.85f,
                     .tip = green,
                     .tipStart = 0.0f,
                     .shadeBase = 0.2f});
    const int leaves = 1 + int(dice() * 3.0f);
    for (int i = 0; i < leaves; ++i) {
        const auto [at, tangent] = alongPolyline(points, dice.range(0.2f, 0.6f));
        const float side = i % 2 == 0 ? 1.0f : -1.0f;
        plant.push_back(leaf(at, rotate(tangent, side * dice.range(0.5f, 0.9f)), S * dice.range(0.08f, 0.13f),
                             S * 0.014f, 0.2f, green * 0.95f, green * 1.1f));
    }
    return points;
}

// Petals as separate strokes, seen from slightly above: the ring is squashed vertically; the far petals are drawn
// first and a little darker, the disc sits on top.
void paintDaisy(Plant& plant, Dice& dice, vec2 centre, float radius, const FlowerStyle& style) {
    const int petals = 11 + int(dice() * 6.0f);
    const float phase = dice.range(0.0f, 2.0f * kPi);
    for (int pass = 0; pass < 2; ++pass)
        for (int k = 0; k < petals; ++k) {
            const float a = phase + 2.0f * kPi * float(k) / float(petals) + dice.range(-0.12f, 0.12f);
            const vec2 d(std::cos(a), std::sin(a) * 0.45f);
            if ((d.y < 0.0f) != (pass == 0)) continue;
            const vec3 c = dice.jitter(style.petals, 0.08f) * (d.y < 0.0f ? 0.85f : 1.0f);
            Stroke s = leaf(centre + d * radius * 0.15f, glm::normalize(d),
                            radius * glm::length(d) * dice.range(0.8f, 1.0f), radius * 0.18f, 0.0f, c * 0.92f, c);
            s.midrib = 0.0f;
            plant.push_back(std::move(s));
        }
    plant.push_back(dot(centre, radius * 0.28f, style.centre, 0.7f));
}

// A spike of small florets, each two short petals either side of the axis, buds at the top.
void paintSpike(Plant& plant, Dice& dice, const std::vector<vec2>& stem, float S, const FlowerStyle& style) {
    const int florets = 14 + int(dice() * 8.0f);
    for (int i = 0; i < florets; ++i) {
        const float t = 0.66f + 0.34f * float(i) / float(florets - 1);
        const auto [at, tangent] = alongPolyline(stem, t);
        const float size = S * (0.022f - 0.011f * (t - 0.66f) / 0.34f);
        const float bud = smoothstep(0.85f, 1.0f, t); // the topmost florets are still buds: darker and greener
        const vec3 c = glm::mix(dice.jitter(style.petals, 0.12f), albedo(0.08f, 0.10f, 0.05f), bud * 0.6f);
        for (float side : {-1.0f, 1.0f})
            plant.push_back(
                leaf(at, rotate(tangent, side * dice.range(0.6f, 1.1f)), size, size * 0.32f, 0.0f, c * 0.85f, c));
    }
}

void paintCup(Plant& plant, Dice& dice, vec2 centre, float radius, const FlowerStyle& style) {
    plant.push_back(dot(centre + vec2(0.0f, -radius * 0.25f), radius * 0.22f, style.centre));
    const float angles[] = {-1.05f, 1.05f, -0.5f, 0.5f, 0.0f}; // side petals first, the front petal last
    for (float a : angles) {
        const vec2 dir = direction(a + dice.range(-0.15f, 0.15f));
        const vec3 c = dice.jitter(style.petals, 0.08f) * (std::abs(a) > 0.8f ? 0.85f : 1.0f);
        Stroke s{.base = c * 0.7f, .tip = c, .tipStart = 0.0f, .sideShade = 0.08f};
        for (int i = 0; i < 8; ++i) {
            const float u = float(i) / 7.0f;
            s.points.push_back(centre + dir * (radius * u));
            s.halfWidths.push_back(radius * 0.4f * (0.3f + 0.7f * std::sin(0.5f * kPi * std::min(1.0f, u * 1.6f))));
        }
        plant.push_back(std::move(s));
    }
}

void paintShrub(Plant& plant, Dice& dice, float S, const FlowerStyle& style) {
    const vec2 centre(S * 0.5f, S * 0.58f);
    const float radius = S * dice.range(0.32f, 0.38f);
    const vec3 bark = albedo(0.10f, 0.075f, 0.05f);
    const int twigs = 5 + int(dice() * 4.0f);
    for (int i = 0; i < twigs; ++i) {
        const vec2 base(S * 0.5f + dice.centred() * S * 0.05f, S);
        const vec2 end = centre + direction(dice.range(-1.2f, 1.2f)) * radius * dice.range(0.5f, 0.9f);
        plant.push_back({.points = cubicBezier(base, glm::mix(base, end, 0.3f) + vec2(dice.centred() * S * 0.03f, 0),
                                               glm::mix(base, end, 0.7f), end, 10),
                         .halfWidths = widths(10, S * 0.006f, [](float t) { return 1.0f - 0.6f * t; }),
                         .base = bark * 0.85f,
                         .tip = bark,
                         .tipStart = 0.0f});
    }
    // Leaves fill a dome; those low and deep inside are a little darker (ambient occlusion of the canopy), a few
    // have yellowed.
    const int leaves = 230 + int(dice() * 60.0f);
    for (int i = 0; i < leaves; ++i) {
        vec2 u(dice.range(-1.0f, 1.0f), dice.range(-1.0f, 1.0f));
        if (glm::dot(u, u) > 1.0f) u *= 0.7f / glm::length(u);
        const vec2 at = centre + u * radius * vec2(1.0f, 0.9f);
        if (at.y > S * 0.97f) continue;
        const float light = 0.75f + 0.15f * (-u.y * 0.5f + 0.5f) + 0.15f * glm::length(u);
        const float length = S * dice.range(0.03f, 0.055f);
        const vec3 green = dice() < 0.08f ? kYellowed : kLeafGreens[dice.pick(3)];
        const vec3 c = dice.jitter(green, 0.12f) * light;
        const vec2 dir = rotate(glm::length(u) > 0.05f ? glm::normalize(u) : vec2(0, -1), dice.range(-0.9f, 0.9f));
        plant.push_back(leaf(at, dir, length, length * 0.3f, 0.1f, c * 0.95f, c * 1.08f));
    }
    const int blossoms = 14 + int(dice() * 10.0f);
    for (int i = 0; i < blossoms; ++i) {
        const float a = dice.range(-1.7f, 1.7f);
        const vec2 at = centre + direction(a) * radius * vec2(1.0f, 0.9f) * dice.range(0.55f, 0.95f);
        if (at.y > S * 0.93f) continue;
        const float r = S * dice.range(0.007f, 0.011f);
        for (int k = 0; k < 5; ++k) {
            const vec2 d = direction(2.0f * kPi * float(k) / 5.0f + a);
            plant.push_back(
                leaf(at, d, r * 1.4f, r * 0.45f, 0.0f, dice.jitter(style.petals, 0.08f) * 0.9f, style.petals));
        }
        plant.push_back(dot(at, r * 0.35f, style.centre));
    }
}

} // namespace

Plant paintGrass(Dice& dice, float S, uint32_t variant) {
    Plant plant;
    const vec2 root(S * 0.5f, S);
    // Variants differ in blade count, spread, height, how far the blades splay and lean, and how dry they are;
    // every third has flowering stems with seed heads.
    const int blades = 70 + int(dice() * 40.0f);
    const float spread = S * dice.range(0.07f, 0.17f);
    const float heightScale = dice.range(0.7f, 1.0f);
    const float splay = dice.range(0.3f, 0.7f), wind = dice.range(-0.25f, 0.25f);
    const GrassMix mix = grassMix(dice, variant);
    paintDeadLeaves(plant, dice, S, 2 + int(dice() * 4.0f), spread * 1.5f); // last year's leaves under the clump

    for (int b = 0; b < blades; ++b) {
        const float off = dice.centred();
        const vec2 base = root + vec2(off * spread, 0.0f);
        const float lean = off * splay + wind + dice.range(-0.3f, 0.3f);
        const float length = S * heightScale * dice.range(0.4f, 0.95f) * (1.0f - 0.25f * std::abs(off));
        const float bend = (lean >= 0.0f ? 1.0f : -1.0f) * (0.1f + 0.9f * dice() * dice());
        BladeShape shape = bladeCentreline(dice, base, lean, bend, length);
        Stroke s{.points = std::move(shape.points), .shadeBase = 0.3f, .sideShade = 0.05f, .midrib = 0.03f};
        colourBlade(s, dice, mix);
        if (shape.broken) s.tip = glm::mix(s.tip, kStraw, 0.5f); // a broken end dries out
        const float halfWidth = S * dice.range(0.004f, 0.008f);
        s.halfWidths = shape.broken ? widths(s.points.size(), halfWidth, [](float t) { return 1.0f - 0.35f * t; })
                                    : widths(s.points.size(), halfWidth, bladeProfile);
        plant.push_back(std::move(s));
    }
    if (variant % 3 == 2) paintSeedHeads(plant, dice, S, variant, spread, heightScale);
    return plant;
}

Plant paintFerns(Dice& dice, float S, uint32_t variant) {
    Plant plant;
    paintDeadLeaves(plant, dice, S, 6 + int(dice() * 6.0f), S * 0.38f);
    const FernHabit habit = fernHabit(dice, variant);
    for (int f = 0; f < habit.fronds; ++f) {
        const float a = habit.fan * (-1.0f + 2.0f * (float(f) + 0.5f + dice.range(-0.3f, 0.3f)) / float(habit.fronds));
        paintFrond(plant, dice, S, habit, a);
    }
    paintDeadLeaves(plant, dice, S, 3, S * 0.38f); // a few leaves in front of the stems
    return plant;
}

Plant paintFlowers(Dice& dice, float S, uint32_t variant) {
    Plant plant;
    const FlowerStyle style = flowerStyle(variant, dice);
    if (style.form == FlowerForm::Shrub) {
        paintShrub(plant, dice, S, style);
        return plant;
    }
    paintRosette(plant, dice, S, 13 + int(dice() * 6.0f));
    // The heads are a small share of the plant: most of a flowering herb is stem and leaf.
    const int stems = style.form == FlowerForm::Cup ? 3 + int(dice() * 3.0f) : 4 + int(dice() * 4.0f);
    for (int i = 0; i < stems; ++i) {
        const float height = S * dice.range(0.5f, 0.9f);
        const auto stem = paintStem(plant, dice, S, height);
        const vec2 top = stem.back();
        switch (style.form) {
        case FlowerForm::Daisy:
            paintDaisy(plant, dice, top, S * dice.range(0.032f, 0.048f), style);
            break;
        case FlowerForm::Spike:
            paintSpike(plant, dice, stem, S, style);
            break;
        case FlowerForm::Cup:
            paintCup(plant, dice, top, S * dice.range(0.04f, 0.055f), style);
            break;
        case FlowerForm::Shrub:
            break;
        }
    }
    return plant;
}

} // namespace sward::atlas_detail
