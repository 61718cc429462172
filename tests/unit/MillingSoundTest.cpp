// The milling sound (issue 13, part 8): the synthesizer's states, loudness,
// determinism, length and smoothness, and the WAV writer's bytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <vector>

#include "millsim/audio/MillingSound.h"
#include "millsim/audio/SoundTrack.h"
#include "millsim/audio/WavFile.h"
#include "millsim/run/HapticLoop.h"

using namespace millsim;

namespace {

constexpr double kRate = 1000.0;  // haptic frames per second
constexpr int kFs = 44100;

// A scripted burr: off, spinning in air, cutting at `removalRate` m³/s with
// `force` N, in air again, off. Times in s.
struct Script {
  double spinOn = 0.5, cutOn = 1.5, cutOff = 2.5, spinOff = 3.5, end = 4.0;
  double removalRate = 1e-9, force = 1.0;
};

std::vector<BurrState> frames(const Script& s) {
  std::vector<BurrState> out;
  double removed = 0.0;
  const long n = std::lround(s.end * kRate);
  for (long i = 0; i < n; ++i) {
    BurrState b;
    b.t = double(i) / kRate;
    b.spinning = b.t >= s.spinOn && b.t < s.spinOff;
    const bool cutting = b.spinning && b.t >= s.cutOn && b.t < s.cutOff;
    if (cutting) removed += s.removalRate / kRate;
    b.removedVolume = removed;
    b.force = cutting ? s.force : 0.0;
    b.contacts = cutting ? 6 : 0;
    out.push_back(b);
  }
  return out;
}

std::vector<std::int16_t> synthesize(const std::vector<BurrState>& in, const MillingSoundParameters& p = {}) {
  MillingSound sound(p);
  std::vector<std::int16_t> out;
  for (const BurrState& b : in) sound.addFrame(b, out);
  sound.finish(in.back().t + 1.0 / kRate, out);
  return out;
}

std::size_t at(double t) { return std::size_t(std::lround(t * kFs)); }

double rms(const std::vector<std::int16_t>& s, double from, double to) {
  double sum = 0.0;
  for (std::size_t i = at(from); i < at(to); ++i) sum += double(s[i]) * double(s[i]);
  return std::sqrt(sum / double(at(to) - at(from)));
}

int maxStep(const std::vector<std::int16_t>& s, double from, double to) {
  int m = 0;
  for (std::size_t i = std::max<std::size_t>(at(from), 1); i < at(to); ++i) m = std::max(m, std::abs(s[i] - s[i - 1]));
  return m;
}

// The largest second difference: a smooth tone's is small, a step's is the step.
int maxKink(const std::vector<std::int16_t>& s, double from, double to) {
  int m = 0;
  for (std::size_t i = std::max<std::size_t>(at(from), 2); i < at(to); ++i)
    m = std::max(m, std::abs(s[i] - 2 * s[i - 1] + s[i - 2]));
  return m;
}

}  // namespace

TEST(MillingSound, SilentUntilTheBurrSpinsAndAfterItStops) {
  Script script;
  script.end = 4.5;
  const auto s = synthesize(frames(script));
  for (std::size_t i = 0; i < at(script.spinOn); ++i) ASSERT_EQ(s[i], 0) << "sample " << i << " before the switch";
  // The motor runs down (release, 80 ms), then is silent: exactly zero, not a tail.
  for (std::size_t i = at(script.spinOff + 0.6); i < s.size(); ++i)
    ASSERT_EQ(s[i], 0) << "sample " << i << " long after the switch went off";
  EXPECT_GT(rms(s, script.spinOn + 0.2, script.cutOn), 100.0) << "spinning in air must be heard";
}

TEST(MillingSound, CuttingIsSeveralTimesLouderThanSpinningInAir) {
  const Script script;
  const auto s = synthesize(frames(script));
  const double air = rms(s, script.spinOn + 0.2, script.cutOn);
  const double air2 = rms(s, script.cutOff + 0.2, script.spinOff);
  const double cut = rms(s, script.cutOn + 0.2, script.cutOff);
  std::printf("RMS (full scale 32768): air %.0f, cutting %.0f (x%.1f), air again %.0f\n", air, cut, cut / air, air2);
  EXPECT_GE(cut, 4.0 * air);
  EXPECT_NEAR(air2, air, 0.05 * air) << "the same state sounds the same";
  EXPECT_LT(cut, 0.5 * 32768.0) << "cutting must not clip";
}

TEST(MillingSound, LoudnessFollowsTheRemovalRateAndTheForce) {
  Script slow, fast, pressed;
  slow.removalRate = 0.2e-9;
  slow.force = 0.0;
  fast.removalRate = 2e-9;
  fast.force = 0.0;
  pressed.removalRate = 0.2e-9;
  pressed.force = 3.0;
  const double a = rms(synthesize(frames(slow)), 1.7, 2.5);
  const double b = rms(synthesize(frames(fast)), 1.7, 2.5);
  const double c = rms(synthesize(frames(pressed)), 1.7, 2.5);
  EXPECT_GT(b, 1.5 * a) << "faster removal must sound louder";
  EXPECT_GT(c, 1.5 * a) << "pressing harder must sound louder";
}

TEST(MillingSound, TheMotorSlowsUnderLoad) {
  // Count upward zero crossings of the tone's fundamental through a low-pass:
  // cutting lowers the pitch. Force only (no removal), so the noise stays small.
  Script script;
  script.removalRate = 0.0;
  script.force = 20.0;
  MillingSoundParameters p;
  p.noiseLevel = 0.0;  // the tone alone
  const auto s = synthesize(frames(script), p);
  auto pitch = [&s](double from, double to) {
    double low = 0.0, prev = 0.0;
    int crossings = 0;
    const double a = 1.0 - std::exp(-2.0 * std::numbers::pi * 1200.0 / kFs);
    for (std::size_t i = at(from); i < at(to); ++i) {
      low += (double(s[i]) - low) * a;
      if (prev < 0.0 && low >= 0.0) ++crossings;
      prev = low;
    }
    return crossings / (to - from);
  };
  const double air = pitch(1.0, 1.5), cut = pitch(2.0, 2.5);
  std::printf("fundamental: air %.0f Hz, cutting %.0f Hz\n", air, cut);
  EXPECT_NEAR(air, p.whineFrequency, 20.0);
  EXPECT_LT(cut, 0.85 * air);
}

TEST(MillingSound, NoClicksWhenTheSwitchOrTheCutStartsOrStops) {
  // A click is a sample-to-sample step larger than the steady sound makes.
  const Script script;
  const auto s = synthesize(frames(script));
  const int steadyAir = maxStep(s, script.spinOn + 0.3, script.cutOn);
  const int steadyCut = maxStep(s, script.cutOn + 0.3, script.cutOff);
  EXPECT_LE(maxStep(s, script.spinOn - 0.01, script.spinOn + 0.1), steadyAir) << "switch on";
  EXPECT_LE(maxStep(s, script.cutOn - 0.01, script.cutOn + 0.1), steadyCut) << "cut starts";
  EXPECT_LE(maxStep(s, script.cutOff - 0.01, script.cutOff + 0.1), steadyCut) << "cut stops";
  EXPECT_LE(maxStep(s, script.spinOff - 0.01, script.spinOff + 0.1), steadyAir) << "switch off";
  // Switched off in the middle of a cut.
  Script abrupt;
  abrupt.spinOff = abrupt.cutOff = 2.0;
  const auto t = synthesize(frames(abrupt));
  EXPECT_LE(maxStep(t, 1.99, 2.1), steadyCut) << "switch off while cutting";
}

TEST(MillingSound, TheToneHasNoKinksWhereTheStateChanges) {
  // The tone alone (no noise), whose steady second differences are small: an
  // envelope that jumped (switch, load) would show as a kink far above them.
  MillingSoundParameters p;
  p.noiseLevel = 0.0;
  const Script script;
  const auto s = synthesize(frames(script), p);
  const int steady = std::max(maxKink(s, script.spinOn + 0.3, script.cutOn), maxKink(s, script.cutOn + 0.3, script.cutOff));
  for (double at : {script.spinOn, script.cutOn, script.cutOff, script.spinOff})
    EXPECT_LE(maxKink(s, at - 0.01, at + 0.1), steady) << "at " << at << " s";
  Script abrupt;
  abrupt.spinOff = abrupt.cutOff = 2.0;
  EXPECT_LE(maxKink(synthesize(frames(abrupt), p), 1.99, 2.1), steady) << "switch off while cutting";
}

TEST(MillingSound, HowFramesAndSamplesAreBatchedChangesNothing) {
  const auto in = frames(Script{});
  const auto whole = synthesize(in);
  // Frames handed over one by one, samples taken in odd-sized pieces.
  MillingSound sound;
  std::vector<std::int16_t> pieces, piece;
  for (std::size_t i = 0; i < in.size(); ++i) {
    sound.addFrame(in[i], piece);
    if (i % 37 == 0) {
      pieces.insert(pieces.end(), piece.begin(), piece.end());
      piece.clear();
    }
  }
  sound.finish(in.back().t + 1.0 / kRate, piece);
  pieces.insert(pieces.end(), piece.begin(), piece.end());
  EXPECT_EQ(pieces, whole);
  EXPECT_EQ(synthesize(in), whole) << "two runs, the same samples";
}

TEST(MillingSound, AsManySamplesAsTheRunLasts) {
  // 4000 frames at 1 kHz: 4 s; and 333 frames at 300 Hz (1.11 s: 48951 samples, a non-integer per frame).
  EXPECT_EQ(synthesize(frames(Script{})).size(), std::size_t(4 * kFs));
  std::vector<BurrState> odd;
  for (int i = 0; i < 333; ++i) odd.push_back(BurrState{double(i) / 300.0, true, 0.0, 0.0, 0});
  MillingSound sound;
  std::vector<std::int16_t> out;
  for (const BurrState& b : odd) sound.addFrame(b, out);
  sound.finish(333.0 / 300.0, out);
  EXPECT_EQ(out.size(), std::size_t(std::llround(333.0 / 300.0 * kFs)));
  EXPECT_EQ(sound.samples(), std::int64_t(out.size()));
}

TEST(MillingSound, NonFiniteForceIsIgnored) {
  auto in = frames(Script{});
  for (auto& b : in)
    if (b.contacts) b.force = std::nan("");
  const auto s = synthesize(in);
  EXPECT_EQ(s.size(), std::size_t(4 * kFs));
  EXPECT_GT(rms(s, 1.7, 2.5), rms(s, 0.7, 1.5)) << "still cutting: the removal rate drives it";
}

TEST(MillingSound, TheMaterialHookChangesTheCut) {
  MillingSoundParameters soft, hard;
  hard.material.hardness = 2.0;
  const auto in = frames(Script{});
  EXPECT_GT(rms(synthesize(in, hard), 1.7, 2.5), 1.3 * rms(synthesize(in, soft), 1.7, 2.5));
  EXPECT_EQ(synthesize(in, hard).size(), synthesize(in, soft).size());
}

TEST(MillingSound, BurrStateOfAFrameRecord) {
  FrameRecord r;
  r.t = 1.25;
  r.button = true;
  r.removedVolume = 2e-9;
  r.force = {3.0, 0.0, 4.0};
  r.out.contacts = 7;
  const BurrState b = burrStateOf(r);
  EXPECT_EQ(b.t, 1.25);
  EXPECT_TRUE(b.spinning);
  EXPECT_EQ(b.removedVolume, 2e-9);
  EXPECT_DOUBLE_EQ(b.force, 5.0);
  EXPECT_EQ(b.contacts, 7);
}

// --- WAV ---

namespace {

std::vector<unsigned char> bytesOf(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
std::uint32_t u32(const std::vector<unsigned char>& b, std::size_t at) {
  return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 |
         std::uint32_t(b[at + 3]) << 24;
}
std::uint16_t u16(const std::vector<unsigned char>& b, std::size_t at) {
  return std::uint16_t(b[at] | b[at + 1] << 8);
}
std::string tag(const std::vector<unsigned char>& b, std::size_t at) { return std::string(b.begin() + long(at), b.begin() + long(at) + 4); }

std::filesystem::path tempWav(const std::string& name) {
  return std::filesystem::path(MILLSIM_BINARY_DIR) / "tests" / ("audio-test-" + name + ".wav");
}

}  // namespace

TEST(WavWriter, HeaderFieldsAndSamples) {
  const auto path = tempWav("header");
  std::vector<std::int16_t> samples;
  for (int i = 0; i < 1001; ++i) samples.push_back(std::int16_t(i * 37 - 20000));
  samples.push_back(-32768);
  samples.push_back(32767);
  {
    WavWriter w(path.string(), 48000);
    w.write(samples.data(), 500);  // in pieces: the file is the same
    w.write(samples.data() + 500, samples.size() - 500);
    EXPECT_EQ(w.samples(), samples.size());
    w.close();
  }
  const auto b = bytesOf(path);
  const std::uint32_t data = std::uint32_t(samples.size() * 2);
  ASSERT_EQ(b.size(), 44 + data);
  EXPECT_EQ(tag(b, 0), "RIFF");
  EXPECT_EQ(u32(b, 4), 36 + data);
  EXPECT_EQ(tag(b, 8), "WAVE");
  EXPECT_EQ(tag(b, 12), "fmt ");
  EXPECT_EQ(u32(b, 16), 16u);
  EXPECT_EQ(u16(b, 20), 1);          // PCM
  EXPECT_EQ(u16(b, 22), 1);          // mono
  EXPECT_EQ(u32(b, 24), 48000u);     // sample rate
  EXPECT_EQ(u32(b, 28), 96000u);     // bytes per second
  EXPECT_EQ(u16(b, 32), 2);          // block align
  EXPECT_EQ(u16(b, 34), 16);         // bits
  EXPECT_EQ(tag(b, 36), "data");
  EXPECT_EQ(u32(b, 40), data);
  for (std::size_t i = 0; i < samples.size(); ++i)
    ASSERT_EQ(std::int16_t(u16(b, 44 + 2 * i)), samples[i]) << "sample " << i;
}

TEST(WavWriter, AnEmptySoundIsAValidFile) {
  const auto path = tempWav("empty");
  WavWriter(path.string(), 44100).close();
  const auto b = bytesOf(path);
  ASSERT_EQ(b.size(), 44u);
  EXPECT_EQ(u32(b, 4), 36u);
  EXPECT_EQ(u32(b, 40), 0u);
}

TEST(WavWriter, TheDestructorFinishesTheHeaderToo) {
  const auto path = tempWav("destructor");
  const std::int16_t s[3] = {1, 2, 3};
  {
    WavWriter w(path.string(), 44100);
    w.write(s, 3);
  }
  const auto b = bytesOf(path);
  ASSERT_EQ(b.size(), 50u);
  EXPECT_EQ(u32(b, 40), 6u);
}

TEST(WavWriter, AnUnwritablePathIsAnErrorNamingIt) {
  try {
    WavWriter w("/nonexistent-folder/sound.wav", 44100);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/sound.wav: cannot write the WAV file"), std::string::npos)
        << e.what();
  }
}

TEST(SoundTrack, WritesWhatItSynthesizesAsLongAsTheRun) {
  const auto path = tempWav("track");
  const auto in = frames(Script{});
  {
    SoundTrack track(path.string());
    FrameRecord r;
    std::vector<std::int16_t> handed;
    for (std::size_t i = 0; i < in.size(); ++i) {
      r.t = in[i].t;
      r.button = in[i].spinning;
      r.removedVolume = in[i].removedVolume;
      r.force = {0.0, in[i].force, 0.0};
      r.out.contacts = in[i].contacts;
      track.add(r);
      if (i % 20 == 0) {
        const auto& f = track.flush();
        handed.insert(handed.end(), f.begin(), f.end());
      }
    }
    const auto& last = track.finish(in.back().t + 1.0 / kRate);
    handed.insert(handed.end(), last.begin(), last.end());
    EXPECT_EQ(handed, synthesize(in)) << "what flush() hands out is the synthesizer's output";
    EXPECT_DOUBLE_EQ(track.seconds(), 4.0);
    EXPECT_GT(track.rms(), 0.0);
  }
  EXPECT_EQ(bytesOf(path).size(), 44u + 2u * 4u * kFs);
}

// Issue 18: the sound changes with the tissue the burr cuts — the same cut in
// enamel (hardness 5) grinds louder than in dentin (1), in the pulp (0.05)
// hardly at all.
TEST(MillingSound, HarderTissueGrindsLouder) {
  const Script s;
  auto in = [&](double hardness) {
    std::vector<BurrState> f = frames(s);
    for (BurrState& b : f) b.hardness = hardness;
    return rms(synthesize(f), 1.7, 2.5);
  };
  const double pulp = in(0.05), dentin = in(1.0), enamel = in(5.0);
  EXPECT_GT(enamel, 1.3 * dentin);
  EXPECT_GT(dentin, 1.3 * pulp);
}
