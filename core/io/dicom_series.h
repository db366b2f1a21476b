// A DICOM series (a folder of slices, as scanners export them) read as a volume for the mri
// scene, by converting it to a temporary NIfTI file with dcm2niix (C. Rorden et al., "The
// first step for neuroimaging data analysis: DICOM to NIfTI conversion", J. Neurosci.
// Methods 264, 2016; Debian package dcm2niix).
//
// Why a converter and not a DICOM library (Debian has GDCM and DCMTK): a library reads
// slices; turning a series into a volume means sorting slices along their normal, checking
// spacing and gantry tilt, mapping DICOM's LPS patient space to NIfTI's RAS, and vendor
// quirks (Siemens mosaics, enhanced multi-frame files). dcm2niix does all of that, is what
// the neuroimaging tools use, and its output goes through the same NIfTI reader (and its
// checks) as any other volume. The price is an external program: without it, a clear
// message says which package to install.
#pragma once

#include <filesystem>

namespace dynamesh {

class ConvertedDicomSeries {
 public:
  // Runs dcm2niix on `folder` into a fresh temporary directory. Throws std::runtime_error
  // (one line) when dcm2niix is missing or fails, when the folder holds no DICOM series, or
  // when it holds more than one (then the user must point at one series' folder).
  explicit ConvertedDicomSeries(const std::filesystem::path& folder);
  ~ConvertedDicomSeries();  // removes the temporary directory
  ConvertedDicomSeries(const ConvertedDicomSeries&) = delete;
  ConvertedDicomSeries& operator=(const ConvertedDicomSeries&) = delete;

  // The converted volume (.nii, valid while this object lives).
  const std::filesystem::path& nifti() const { return nifti_; }

 private:
  std::filesystem::path temporary_, nifti_;
};

}  // namespace dynamesh
