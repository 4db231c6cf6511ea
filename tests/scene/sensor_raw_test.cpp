// The camera's digital output (scene/sensor_raw.h): the DN of chosen signals, the clip, the white level with a
// black level and full well, the DN the sensor model hands out, and the key's parse and write-back.
#include "scene/sensor_model.h"
#include "scene/sensor_raw.h"

#include "common/error.h"
#include "common/half_float.h"
#include "test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

using namespace sward;

namespace {

SensorParams parse(const nlohmann::json& j) {
    return parseSensor(j, "scene.json", "camera.sensor");
}

std::string message(const nlohmann::json& j) {
    return test::errorOf([&] { parse(j); });
}

} // namespace

TEST(SensorRaw, DigitalNumbersRoundHalfUpAtEachBitDepth) {
    EXPECT_EQ(rawDigitalNumber(0.5, 1.0, 8), 128u);    // 127.5 rounds up
    EXPECT_EQ(rawDigitalNumber(0.5, 1.0, 12), 2048u);  // 2047.5
    EXPECT_EQ(rawDigitalNumber(0.5, 1.0, 16), 32768u); // 32767.5
    EXPECT_EQ(rawDigitalNumber(0.25, 1.0, 10), 256u);  // 255.75
    EXPECT_EQ(rawDigitalNumber(0.25, 1.0, 14), 4096u); // 4095.75
    EXPECT_EQ(rawDigitalNumber(100.0 / 4095.0, 1.0, 12), 100u);
    EXPECT_EQ(rawDigitalNumber(100.4 / 4095.0, 1.0, 12), 100u);
    EXPECT_EQ(rawDigitalNumber(100.6 / 4095.0, 1.0, 12), 101u);
    EXPECT_EQ(rawDigitalNumber(0.25, 0.5, 12), 2048u); // the white level scales the signal
}

TEST(SensorRaw, TheAdcClipsAtItsWhiteLevelAndFloorsAtZero) {
    const double inf = std::numeric_limits<double>::infinity();
    for (uint32_t bits : kRawBitDepths) {
        const uint32_t full = (1u << bits) - 1;
        EXPECT_EQ(rawDigitalNumber(1.0, 1.0, bits), full) << bits;
        EXPECT_EQ(rawDigitalNumber(3.0, 1.0, bits), full) << bits;
        EXPECT_EQ(rawDigitalNumber(inf, 1.0, bits), full) << bits;
        EXPECT_EQ(rawDigitalNumber(0.0, 1.0, bits), 0u) << bits;
        EXPECT_EQ(rawDigitalNumber(-0.2, 1.0, bits), 0u) << bits; // zero-mean noise below the floor
        EXPECT_EQ(rawDigitalNumber(std::nan(""), 1.0, bits), 0u) << bits;
    }
    EXPECT_THROW(rawDigitalNumber(0.5, 1.0, 9), Error);
}

TEST(SensorRaw, TheWhiteLevelIsTheBlackLevelPlusTheFullWell) {
    EXPECT_EQ(rawWhiteLevel(parse({{"bit_depth", 12}})), 1.0);
    EXPECT_EQ(rawWhiteLevel(parse({{"bit_depth", 12}, {"black_level", 0.0625}})), 1.0); // no well: 1 is full scale
    const SensorParams camera =
        parse({{"bit_depth", 12}, {"electrons_per_unit", 1000}, {"full_well", 4000}, {"black_level", 0.0625}});
    EXPECT_EQ(rawWhiteLevel(camera), 4.0625);
    // A black pixel reads the pedestal: 0.0625 / 4.0625 * 4095 = 63.0 DN; the well's clip reads full scale.
    EXPECT_EQ(rawDigitalNumber(0.0625, rawWhiteLevel(camera), 12), 63u);
    EXPECT_EQ(rawDigitalNumber(4.0625, rawWhiteLevel(camera), 12), 4095u);
}

// The sensor model hands out the DN of its float output (before the half rounding), alpha dropped. Half keeps 11
// significant bits, so a value v is off by at most 2^-11 of the power of two below it: 4095 * 2^-11 * 2^e / white
// DN, under 1 when the white level is a power of two (here 0.0625 + 1875 / 2000 = 1), under 2 otherwise.
TEST(SensorRaw, TheSensorModelDigitisesItsFloatOutput) {
    const SensorParams p = parse({{"bit_depth", 12},
                                  {"electrons_per_unit", 2000},
                                  {"read_noise", 3},
                                  {"full_well", 1875},
                                  {"black_level", 0.0625}});
    const Intrinsics camera{50.0, 50.0, 16.0, 12.0, 32, 24};
    std::vector<float> rgba(size_t(32) * 24 * 4, 1.0f);
    for (size_t i = 0; i < rgba.size(); ++i)
        if (i % 4 != 3) rgba[i] = float(i % 97) / 48.0f; // 0 .. 2: past the well's clip at 0.9375
    std::vector<uint16_t> half(rgba.size());
    for (size_t i = 0; i < rgba.size(); ++i) half[i] = floatToHalfBits(rgba[i]);
    std::vector<float> floatOut(rgba.size());
    for (size_t i = 0; i < rgba.size(); ++i) floatOut[i] = halfBitsToFloat(half[i]);
    const SensorModel model(p, camera);
    model.apply(7, 3, 0, floatOut);
    std::vector<uint16_t> digital;
    model.applyHalf(7, 3, 0, half, 1.0, &digital);
    ASSERT_EQ(digital.size(), size_t(32) * 24 * 3);
    EXPECT_EQ(digital, rawDigitalImage(p, floatOut, 32));
    uint32_t clipped = 0, maxDifference = 0;
    for (size_t px = 0; px < size_t(32) * 24; ++px)
        for (size_t c = 0; c < 3; ++c) {
            const uint16_t fromHalf = rawDigitalNumber(halfBitsToFloat(half[px * 4 + c]), rawWhiteLevel(p), 12);
            maxDifference = std::max<uint32_t>(maxDifference, std::abs(int(fromHalf) - int(digital[px * 3 + c])));
            clipped += digital[px * 3 + c] == 4095;
        }
    EXPECT_LE(maxDifference, 1u);
    EXPECT_GT(clipped, 100u);
    std::vector<uint16_t> none;
    SensorModel(parse({{"electrons_per_unit", 2000}}), camera).applyHalf(7, 3, 0, half, 1.0, &none);
    EXPECT_TRUE(none.empty()); // no bit depth: no digital output
}

TEST(SensorRaw, TheBitDepthIsWrittenBackOnlyWhenSet) {
    EXPECT_EQ(parse({{"bit_depth", 14}}).bitDepth, 14u);
    EXPECT_EQ(sensorToJson(parse({{"bit_depth", 14}})).at("bit_depth"), 14);
    EXPECT_FALSE(sensorToJson(parse({{"exposure", 2}})).contains("bit_depth"));
    EXPECT_FALSE(sensorToJson(parse({{"bit_depth", 0}})).contains("bit_depth"));
    EXPECT_EQ(sensorToJson(parse({{"bit_depth", 0}})), sensorToJson(parse(nlohmann::json::object())));
}

TEST(SensorRaw, BadBitDepthsAreRefusedNamingTheKey) {
    const std::string bad = "scene.json: 'camera.sensor.bit_depth' must be 0 (no digital output), 8, 10, 12, 14 or 16";
    EXPECT_EQ(message({{"bit_depth", 7}}), bad + " (got 7)");
    EXPECT_EQ(message({{"bit_depth", 17}}), bad + " (got 17)");
    EXPECT_EQ(message({{"bit_depth", -1}}), bad + " (got -1)");
    EXPECT_EQ(message({{"bit_depth", "12"}}), bad + " (got \"12\")");
    EXPECT_EQ(message({{"bit_depth", 12.5}}), bad + " (got 12.5)");
    EXPECT_EQ(message({{"bit_depth", 12.0}}), bad + " (got 12.0)");
    EXPECT_EQ(message({{"enabled", false}, {"bit_depth", 12}}),
              "scene.json: 'camera.sensor.bit_depth' needs an enabled sensor (the sensor has 'enabled': false)");
    EXPECT_EQ(message({{"enabled", false}, {"bit_depth", 0}}), "");
}
