#pragma once
// Renders a LaparoscopeView in-process into an RGB buffer (needs an X display: the test binary
// runs under xvfb-run), with the pixel helpers the render tests share.

#include <vtkImageData.h>
#include <vtkPNGWriter.h>
#include <vtkRenderWindow.h>
#include <vtkSmartPointer.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "app/render/laparoscope_view.h"

namespace vesica::app::testing {

struct Rgb {
  int r = 0, g = 0, b = 0;
};

/// Rec. 709 luma of an 8-bit pixel.
inline double Luminance(Rgb c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

/// An RGB picture, row 0 at the top (VTK's start at the bottom).
class Picture {
 public:
  Picture() = default;
  Picture(int w, int h) : w_(w), h_(h), rgb_(static_cast<std::size_t>(3) * w * h) {}
  int width() const { return w_; }
  int height() const { return h_; }
  bool contains(int col, int row) const { return col >= 0 && row >= 0 && col < w_ && row < h_; }
  Rgb at(int col, int row) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(row) * w_ + col);
    return {rgb_[i], rgb_[i + 1], rgb_[i + 2]};
  }
  std::uint8_t* data() { return rgb_.data(); }

 private:
  int w_ = 0, h_ = 0;
  std::vector<std::uint8_t> rgb_;
};

/// One off-screen window, reused across renders (as the trainer reuses its window).
class OffscreenRender {
 public:
  OffscreenRender(int width, int height) : width_(width), height_(height) {
    window_ = vtkSmartPointer<vtkRenderWindow>::New();
    window_->SetOffScreenRendering(1);
    window_->SetMultiSamples(0);  // translucency under Mesa needs it off (shared notes)
    window_->SetAlphaBitPlanes(1);
    window_->SetSize(width, height);
  }
  ~OffscreenRender() {
    if (attached_) window_->RemoveRenderer(attached_);
  }
  OffscreenRender(const OffscreenRender&) = delete;
  OffscreenRender& operator=(const OffscreenRender&) = delete;

  Picture Render(LaparoscopeView& view) {
    if (attached_ != view.renderer()) {
      if (attached_) window_->RemoveRenderer(attached_);
      attached_ = view.renderer();
      window_->AddRenderer(attached_);
    }
    window_->Render();
    auto grab = vtkSmartPointer<vtkWindowToImageFilter>::New();
    grab->SetInput(window_);
    grab->ReadFrontBufferOff();
    grab->SetInputBufferTypeToRGB();
    grab->Update();
    vtkImageData* img = grab->GetOutput();
    Picture pic(width_, height_);
    const int comps = img->GetNumberOfScalarComponents();
    for (int row = 0; row < height_; ++row)
      for (int col = 0; col < width_; ++col) {
        const auto* p = static_cast<const unsigned char*>(img->GetScalarPointer(col, height_ - 1 - row, 0));
        std::copy(p, p + std::min(comps, 3), pic.data() + 3 * (static_cast<std::size_t>(row) * width_ + col));
      }
    last_ = grab;
    return pic;
  }

  /// Writes the last render as PNG (for looking at a failing test's picture).
  void SaveLast(const std::filesystem::path& png) {
    if (!last_) return;
    auto writer = vtkSmartPointer<vtkPNGWriter>::New();
    writer->SetFileName(png.string().c_str());
    writer->SetInputConnection(last_->GetOutputPort());
    writer->Write();
  }

 private:
  int width_, height_;
  vtkSmartPointer<vtkRenderWindow> window_;
  vtkSmartPointer<vtkWindowToImageFilter> last_;
  vtkRenderer* attached_ = nullptr;
};

}  // namespace vesica::app::testing
