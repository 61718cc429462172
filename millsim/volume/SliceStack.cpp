// Slice stacks (VolumeIO.h, readSliceStack): one greyscale TIFF, PNG or BMP
// per slice in a folder or a printf-style pattern, or the pages of one
// multi-page TIFF, as micro-CT scanners of extracted teeth write them. libtiff
// reads every TIFF page (strips or tiles, any compression it knows), libpng
// every PNG (rows read one by one, 16-bit samples exactly as stored: no
// gamma), SDL2 every BMP (BmpSlice.h); MillSim checks the shape of each
// against the first before reading its pixels, and streams the slices into a
// VolumeBuilder a row at a time, so memory is the sparse grid and one slab.
// The pixel size comes from the VolumeObject's voxelSize, a SkyScan-style
// .log beside the slices ("Image Pixel Size (um)="), or the TIFF resolution
// tags or PNG pHYs chunk, in that order (not a BMP's pixels per metre: tools
// write 72 or 96 dpi there whatever the scan); slices are as far apart as
// pixels are wide.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <csetjmp>

#include <glm/vec2.hpp>
#include <png.h>
#include <tiffio.h>

#include "millsim/core/NaturalOrder.h"
#include "millsim/volume/BmpSlice.h"
#include "millsim/volume/MedicalModule.h"
#include "millsim/volume/ReaderLimits.h"
#include "millsim/volume/VolumeBuilder.h"
#include "millsim/volume/VolumeError.h"
#include "millsim/volume/VolumeIO.h"

namespace millsim {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxSlices = 20000;

// libtiff reports through process-wide handlers; the last message of a read
// is kept for its error (reads are serial: the loader holds no lock across them).
thread_local std::string tiffMessage;
void keepTiffMessage(const char* module, const char* fmtText, va_list args) {
  char text[512];
  std::vsnprintf(text, sizeof text, fmtText, args);
  tiffMessage = std::string(module ? module : "libtiff") + ": " + text;
}
void ignoreTiffWarning(const char*, const char*, va_list) {}

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};
using TiffFile = std::unique_ptr<TIFF, TiffCloser>;

TiffFile openTiff(const fs::path& file) {
  TIFFSetErrorHandler(keepTiffMessage);
  TIFFSetWarningHandler(ignoreTiffWarning);
  tiffMessage.clear();
  TiffFile t(TIFFOpen(file.c_str(), "r"));
  if (!t) throw VolumeError(file.string() + ": not a TIFF file libtiff can read (" + tiffMessage + ")");
  return t;
}

struct Page {
  glm::ivec2 size{0};
  int bits = 0;
  bool isSigned = false, isFloat = false, minIsWhite = false;
  double pixelMm = 0.0;  // from the resolution tags; 0 when they say nothing
};

Page pageOf(TIFF* t, const std::string& where) {
  std::uint32_t w = 0, h = 0;
  std::uint16_t bits = 1, samples = 1, format = SAMPLEFORMAT_UINT, photometric = PHOTOMETRIC_MINISBLACK, unit = RESUNIT_INCH;
  TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &w);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &h);
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &samples);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &format);
  TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &photometric);
  if (samples != 1)
    throw VolumeError(where + " has " + std::to_string(samples) + " samples a pixel; a slice is one grey channel");
  if (photometric != PHOTOMETRIC_MINISBLACK && photometric != PHOTOMETRIC_MINISWHITE)
    throw VolumeError(where + " is not greyscale (photometric " + std::to_string(photometric) + ")");
  const bool isFloat = format == SAMPLEFORMAT_IEEEFP;
  if (isFloat ? bits != 32 : !(bits == 8 || bits == 16))
    throw VolumeError(where + " has " + std::to_string(bits) + "-bit pixels; slices are 8 or 16-bit integers (or 32-bit float)");
  if (w == 0 || h == 0 || w > (1u << 16) || h > (1u << 16))
    throw VolumeError(where + " is " + std::to_string(w) + " × " + std::to_string(h) + " pixels; expected 1 to 65536 a side");
  Page p{glm::ivec2(int(w), int(h)), bits, format == SAMPLEFORMAT_INT, isFloat, photometric == PHOTOMETRIC_MINISWHITE, 0.0};
  float xres = 0.f;
  if (TIFFGetField(t, TIFFTAG_XRESOLUTION, &xres) && xres > 0.f && std::isfinite(xres)) {
    TIFFGetFieldDefaulted(t, TIFFTAG_RESOLUTIONUNIT, &unit);
    if (unit == RESUNIT_CENTIMETER) p.pixelMm = 10.0 / double(xres);
    if (unit == RESUNIT_INCH) p.pixelMm = 25.4 / double(xres);
  }
  return p;
}

std::string describe(const Page& p) {
  return std::to_string(p.size.x) + " × " + std::to_string(p.size.y) + " pixels of " + std::to_string(p.bits) + "-bit " +
         (p.isFloat ? "floats" : p.isSigned ? "signed integers" : "integers");
}

// The next page of a multi-page TIFF; false at the last. A directory that
// cannot be read (a file cut inside its pages) is an error, not the end.
bool nextPage(TIFF* t, const std::string& name) {
  tiffMessage.clear();
  const bool more = TIFFReadDirectory(t) != 0;
  if (!tiffMessage.empty()) throw VolumeError(name + ": a page cannot be read (" + tiffMessage + "); is the file cut short?");
  return more;
}

// One row of a page's samples (host order, as libtiff gives them) as densities.
void rowToDensities(const unsigned char* row, const Page& p, float* values) {
  const double white = p.bits == 8 ? 255.0 : 65535.0;
  for (int x = 0; x < p.size.x; ++x) {
    double v;
    if (p.bits == 8) {
      v = p.isSigned ? double(std::int8_t(row[std::size_t(x)])) : double(row[std::size_t(x)]);
    } else if (p.bits == 16) {
      std::uint16_t u;
      std::memcpy(&u, &row[std::size_t(x) * 2], 2);
      v = p.isSigned ? double(std::int16_t(u)) : double(u);
    } else {
      float f;
      std::memcpy(&f, &row[std::size_t(x) * 4], 4);
      v = double(f);
    }
    if (p.minIsWhite && !p.isFloat) v = white - v;
    values[x] = float(v);
  }
}

// A tiled page (as some scanners and image tools write large slices) is read
// a band of tiles at a time: one tile's height of whole rows, so memory stays
// one band whatever the page's size.
constexpr std::size_t kMaxTileBandBytes = std::size_t(256) << 20;

void readTiledPage(TIFF* t, const Page& p, VolumeBuilder& builder, const std::string& where) {
  std::uint32_t tw = 0, th = 0;
  TIFFGetField(t, TIFFTAG_TILEWIDTH, &tw);
  TIFFGetField(t, TIFFTAG_TILELENGTH, &th);
  const std::size_t bytes = std::size_t(p.bits / 8);
  if (tw == 0 || th == 0 || tw > (1u << 16) || th > (1u << 16))
    throw VolumeError(where + " has tiles of " + std::to_string(tw) + " × " + std::to_string(th) +
                      " pixels; expected 1 to 65536 a side");
  const std::size_t tilesAcross = (std::size_t(p.size.x) + tw - 1) / tw;
  const std::size_t bandWidth = tilesAcross * tw;  // whole tiles: the last may overhang the page
  if (bandWidth * th * bytes > kMaxTileBandBytes)
    throw VolumeError(where + " has tiles of " + std::to_string(tw) + " × " + std::to_string(th) +
                      " pixels: a row of them is more than " + std::to_string(kMaxTileBandBytes >> 20) +
                      " MiB; save the slices in strips or smaller tiles");
  const std::size_t tileBytes = std::size_t(tw) * th * bytes;
  if (TIFFTileSize(t) < tmsize_t(tileBytes)) throw VolumeError(where + ": its tiles are smaller than their size says");
  std::vector<unsigned char> tile(std::size_t(TIFFTileSize(t))), band(bandWidth * th * bytes);
  std::vector<float> values(std::size_t(p.size.x));
  for (std::uint32_t y0 = 0; y0 < std::uint32_t(p.size.y); y0 += th) {
    for (std::size_t i = 0; i < tilesAcross; ++i) {
      tiffMessage.clear();
      const std::uint32_t x0 = std::uint32_t(i * tw);
      if (TIFFReadTile(t, tile.data(), x0, y0, 0, 0) < 0)
        throw VolumeError(where + ": the tile at pixel (" + std::to_string(x0) + ", " + std::to_string(y0) +
                          ") cannot be read (" + tiffMessage + "); is the file cut short?");
      for (std::uint32_t r = 0; r < th; ++r)
        std::memcpy(&band[(std::size_t(r) * bandWidth + x0) * bytes], &tile[std::size_t(r) * tw * bytes], tw * bytes);
    }
    for (std::uint32_t r = 0; r < th && y0 + r < std::uint32_t(p.size.y); ++r) {
      rowToDensities(&band[std::size_t(r) * bandWidth * bytes], p, values.data());
      builder.append(values.data(), values.size());
    }
  }
}

// One page's rows into the builder, as densities.
void readPage(TIFF* t, const Page& p, VolumeBuilder& builder, const std::string& where) {
  if (TIFFIsTiled(t)) return readTiledPage(t, p, builder, where);
  std::vector<unsigned char> row(std::size_t(TIFFScanlineSize(t)));
  if (row.size() < std::size_t(p.size.x) * std::size_t(p.bits / 8))
    throw VolumeError(where + ": its rows are shorter than its width says");
  std::vector<float> values(std::size_t(p.size.x));
  for (int y = 0; y < p.size.y; ++y) {
    tiffMessage.clear();
    if (TIFFReadScanline(t, row.data(), std::uint32_t(y), 0) < 0)
      throw VolumeError(where + ": row " + std::to_string(y) + " cannot be read (" + tiffMessage + "); is the file cut short?");
    rowToDensities(row.data(), p, values.data());
    builder.append(values.data(), values.size());
  }
}

// One PNG slice, read with libpng's row API: its errors longjmp back into
// the call that set the jump, which throws (nothing with a destructor is
// made between the setjmp and the libpng calls it guards).
class PngSlice {
public:
  explicit PngSlice(const fs::path& file) : name_(file.string()) {
    file_ = std::fopen(file.c_str(), "rb");
    if (!file_) throw VolumeError(name_ + ": cannot open it");
    unsigned char magic[8] = {};
    if (std::fread(magic, 1, 8, file_) != 8 || png_sig_cmp(magic, 0, 8) != 0)
      throw VolumeError(name_ + ": not a PNG file (its first bytes are not PNG's signature)");
    png_ = png_create_read_struct(PNG_LIBPNG_VER_STRING, this, &PngSlice::onError, &PngSlice::onWarning);
    info_ = png_ ? png_create_info_struct(png_) : nullptr;
    if (!info_) throw VolumeError(name_ + ": libpng could not start");
    if (setjmp(png_jmpbuf(png_))) throw VolumeError(name_ + ": not a PNG libpng can read (" + message_ + ")");
    png_init_io(png_, file_);
    png_set_sig_bytes(png_, 8);
    png_read_info(png_, info_);
  }
  PngSlice(const PngSlice&) = delete;
  PngSlice& operator=(const PngSlice&) = delete;

  Page page() {
    if (setjmp(png_jmpbuf(png_))) throw VolumeError(name_ + ": " + message_);
    const png_uint_32 w = png_get_image_width(png_, info_), h = png_get_image_height(png_, info_);
    const int bits = png_get_bit_depth(png_, info_), colour = png_get_color_type(png_, info_);
    if (colour != PNG_COLOR_TYPE_GRAY)
      throw VolumeError(name_ + " is not one grey channel (PNG colour type " + std::to_string(colour) +
                        "); a slice is greyscale without alpha");
    if (bits != 8 && bits != 16)
      throw VolumeError(name_ + " has " + std::to_string(bits) + "-bit pixels; slices are 8 or 16-bit");
    if (w == 0 || h == 0 || w > (1u << 16) || h > (1u << 16))
      throw VolumeError(name_ + " is " + std::to_string(w) + " × " + std::to_string(h) + " pixels; expected 1 to 65536 a side");
    if (png_get_interlace_type(png_, info_) != PNG_INTERLACE_NONE)
      throw VolumeError(name_ + " is interlaced; slices are read by rows: save them without interlacing");
    Page p{glm::ivec2(int(w), int(h)), bits, false, false, false, 0.0};
    png_uint_32 xppm = 0, yppm = 0;
    int unit = 0;
    if (png_get_pHYs(png_, info_, &xppm, &yppm, &unit) && unit == PNG_RESOLUTION_METER && xppm > 0)
      p.pixelMm = 1000.0 / double(xppm);
    return p;
  }

  void read(const Page& p, VolumeBuilder& builder) {
    // The buffers are members: nothing is constructed between the setjmp and the longjmp.
    row_.assign(std::size_t(p.size.x) * std::size_t(p.bits / 8), 0);
    values_.assign(std::size_t(p.size.x), 0.f);
    if (setjmp(png_jmpbuf(png_))) throw VolumeError(name_ + ": " + message_ + "; is the file cut short?");
    for (int y = 0; y < p.size.y; ++y) {
      png_read_row(png_, row_.data(), nullptr);
      for (int x = 0; x < p.size.x; ++x)
        // PNG stores 16-bit samples big-endian.
        values_[std::size_t(x)] = p.bits == 8 ? float(row_[std::size_t(x)])
                                              : float(unsigned(row_[std::size_t(x) * 2]) << 8 | row_[std::size_t(x) * 2 + 1]);
      builder.append(values_.data(), values_.size());
    }
  }

private:
  static void onError(png_structp png, png_const_charp message) {
    auto* self = static_cast<PngSlice*>(png_get_error_ptr(png));
    self->message_ = message ? message : "libpng error";
    png_longjmp(png, 1);
  }
  static void onWarning(png_structp, png_const_charp) {}

  // Freed by a member's destructor, so that a constructor that throws frees them too.
  struct Handles {
    std::FILE* file = nullptr;
    png_structp png = nullptr;
    png_infop info = nullptr;
    Handles() = default;
    Handles(const Handles&) = delete;
    Handles& operator=(const Handles&) = delete;
    ~Handles() {
      if (png) png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
      if (file) std::fclose(file);
    }
  };

  std::string name_, message_;
  std::vector<unsigned char> row_;
  std::vector<float> values_;
  Handles handles_;
  std::FILE*& file_ = handles_.file;
  png_structp& png_ = handles_.png;
  png_infop& info_ = handles_.info;
};

bool isTiff(const fs::path& p) {
  const std::string ext = asciiLower(p.extension().string());
  return ext == ".tif" || ext == ".tiff";
}

bool isPng(const fs::path& p) { return asciiLower(p.extension().string()) == ".png"; }

bool isBmp(const fs::path& p) { return asciiLower(p.extension().string()) == ".bmp"; }

enum class SliceKind { tiff, png, bmp };

SliceKind kindOf(const fs::path& p) { return isPng(p) ? SliceKind::png : isBmp(p) ? SliceKind::bmp : SliceKind::tiff; }

const char* kindName(SliceKind k) { return k == SliceKind::png ? "PNG" : k == SliceKind::bmp ? "BMP" : "TIFF"; }

// A BMP slice's shape: 8-bit grey, no resolution (BmpSlice.h).
Page bmpPage(glm::ivec2 size) { return Page{size, 8, false, false, false, 0.0}; }

// One BMP slice's rows into the builder (8-bit grey).
void readBmp(const medical::BmpSlice& slice, VolumeBuilder& builder) {
  std::vector<float> values(std::size_t(slice.size().x));
  for (int y = 0; y < slice.size().y; ++y) {
    const unsigned char* row = slice.row(y);
    for (std::size_t x = 0; x < values.size(); ++x) values[x] = float(row[x]);
    builder.append(values.data(), values.size());
  }
}

// "Image Pixel Size (um)=12.5" in a .log beside the slices (SkyScan's reconstruction log).
std::optional<double> pixelSizeFromLog(const fs::path& folder) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    if (asciiLower(e.path().extension().string()) != ".log" || !e.is_regular_file(ec)) continue;
    // A reconstruction log is a few kilobytes: read its first 64 KB, whatever the file is.
    std::ifstream in(e.path(), std::ios::binary);
    std::string text(64 * 1024, '\0');
    in.read(text.data(), std::streamsize(text.size()));
    text.resize(std::size_t(in.gcount()));
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
      const std::size_t at = line.find("Image Pixel Size (um)=");
      if (at == std::string::npos) continue;
      try {
        const double um = std::stod(line.substr(at + 22));
        if (um > 0.0 && std::isfinite(um)) return um * 1e-3;
      } catch (const std::exception&) {
      }
    }
  }
  return std::nullopt;
}

}  // namespace

namespace {

std::vector<fs::path> sliceFiles(const fs::path& folderOrPattern) {
  std::vector<fs::path> files;
  const std::string text = folderOrPattern.string();
  if (isSliceStackPattern(text)) {
    // The first index that exists among 0 … 9, then every next one until one is missing.
    auto name = [&](std::size_t i) {
      std::vector<char> buf(text.size() + 32);
      std::snprintf(buf.data(), buf.size(), text.c_str(), int(i));
      return fs::path(buf.data());
    };
    std::size_t first = 0;
    while (first < 10 && !fs::exists(name(first))) ++first;
    if (first == 10) throw VolumeError(text + ": no slice file matches the pattern (tried indices 0 to 9 for the first)");
    for (std::size_t i = first; fs::exists(name(i)); ++i) {
      if (files.size() == kMaxSlices)
        throw VolumeError(text + ": more than " + std::to_string(kMaxSlices) + " slices; MillSim reads at most that many");
      files.push_back(name(i));
    }
    return files;
  }
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folderOrPattern, ec))
    if (e.is_regular_file(ec) && isSliceImageFile(e.path())) {
      if (files.size() == kMaxSlices)
        throw VolumeError(text + ": more than " + std::to_string(kMaxSlices) + " slices; MillSim reads at most that many");
      files.push_back(e.path());
    }
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    return naturalLess(a.filename().string(), b.filename().string());
  });
  if (files.empty()) throw VolumeError(text + ": no .tif, .tiff, .png or .bmp slices in the folder");
  // One kind a stack: a TIFF stack with a PNG preview beside it is not a stack of both.
  for (const fs::path& f : files)
    if (kindOf(f) != kindOf(files[0]))
      throw VolumeError(text + " holds both " + kindName(std::min(kindOf(files[0]), kindOf(f))) + " and " +
                        kindName(std::max(kindOf(files[0]), kindOf(f))) + " slices (" +
                        files[0].filename().string() + ", " + f.filename().string() +
                        "); a stack is one kind: move the others out");
  return files;
}

}  // namespace

VoxelVolume medical::readSliceStack(const fs::path& source, float airValue, glm::dvec3 voxelSize) {
  // A single .tif: its pages are the slices; else one file a slice.
  const bool onePerFile = !(fs::is_regular_file(source) && isTiff(source));
  const std::vector<fs::path> files = onePerFile ? sliceFiles(source) : std::vector<fs::path>{source};
  const std::string name = source.string();
  const SliceKind kind = kindOf(files[0]);
  const bool png = kind == SliceKind::png, bmp = kind == SliceKind::bmp;

  // The shape: every page must match the first.
  TiffFile first = png || bmp ? nullptr : openTiff(files[0]);
  const Page shape = png   ? PngSlice(files[0]).page()
                     : bmp ? bmpPage(medical::BmpSlice::headerSize(files[0]))
                           : pageOf(first.get(), files[0].string());
  std::size_t slices = files.size();
  if (!onePerFile) {
    slices = 0;
    do {
      const Page p = pageOf(first.get(), name + " page " + std::to_string(slices + 1));
      if (p.size != shape.size || p.bits != shape.bits || p.isFloat != shape.isFloat)
        throw VolumeError(name + " page " + std::to_string(slices + 1) + " is " + describe(p) + "; the first is " + describe(shape));
      if (++slices > kMaxSlices)
        throw VolumeError(name + ": more than " + std::to_string(kMaxSlices) + " pages; MillSim reads at most that many");
    } while (nextPage(first.get(), name));
    TIFFSetDirectory(first.get(), 0);
  }

  // The pixel size: the VolumeObject's, a SkyScan .log's, or the tags'.
  if (!(voxelSize.x > 0.0)) {
    const fs::path folder = onePerFile ? fs::path(files[0]).parent_path() : source.parent_path();
    if (const auto mm = pixelSizeFromLog(folder.empty() ? fs::path(".") : folder)) voxelSize = glm::dvec3(*mm * 1e-3);
    else if (shape.pixelMm > 0.0) voxelSize = glm::dvec3(shape.pixelMm * 1e-3);
    else
      throw VolumeError(name + ": no pixel size in " +
                        (png ? "the PNG pHYs chunk or in " : bmp ? "" : "the TIFF resolution tags or in ") +
                        "a SkyScan .log beside the slices; give the VolumeObject's voxelSize");
  }

  VolumeBuilder builder(glm::ivec3(shape.size.x, shape.size.y, int(slices)), voxelSize, airValue, name);
  auto mismatch = [&](const fs::path& f, const Page& p) {
    if (p.size != shape.size || p.bits != shape.bits || p.isFloat != shape.isFloat)
      throw VolumeError(f.string() + " is " + describe(p) + "; the first slice, " + files[0].filename().string() +
                        ", is " + describe(shape));
  };
  if (bmp) {
    for (const fs::path& f : files) {
      const medical::BmpSlice slice(f);
      mismatch(f, bmpPage(slice.size()));
      readBmp(slice, builder);
    }
  } else if (png) {
    for (const fs::path& f : files) {
      PngSlice slice(f);
      const Page p = slice.page();
      mismatch(f, p);
      slice.read(p, builder);
    }
  } else if (onePerFile) {
    readPage(first.get(), shape, builder, files[0].string());
    first.reset();
    for (std::size_t i = 1; i < files.size(); ++i) {
      TiffFile t = openTiff(files[i]);
      const Page p = pageOf(t.get(), files[i].string());
      mismatch(files[i], p);
      readPage(t.get(), p, builder, files[i].string());
    }
  } else {
    std::size_t page = 0;
    do readPage(first.get(), pageOf(first.get(), name), builder, name + " page " + std::to_string(++page));
    while (nextPage(first.get(), name));
  }
  return builder.finish();
}

}  // namespace millsim
