#!/usr/bin/python3
"""Writes a small MR DICOM series for the tests: a bright ball in a dark box.

Usage: make_dicom_series.py DIR [--columns 64 --rows 56 --slices 48 --spacing 2.0 2.0 2.5
                                  --radius 30 --centre 10 20 30 --prefix IM]

One file per slice (MR Image Storage, explicit VR little endian, 16-bit unsigned), the
slices axial, listed in a shuffled order (a reader must sort them by position, not by file
name). Patient coordinates (DICOM's LPS, mm): voxel (i, j, k) lies at
(x0 + i * dx, y0 + j * dy, z0 + k * dz), with the ball centred at --centre. Needs Debian's
python3-pydicom.
"""
import argparse
import math
import os
import random

import pydicom
from pydicom.dataset import FileDataset, FileMetaDataset
from pydicom.uid import ExplicitVRLittleEndian, generate_uid

MR_IMAGE_STORAGE = "1.2.840.10008.5.1.4.1.1.4"


def main():
    p = argparse.ArgumentParser()
    p.add_argument("dir")
    p.add_argument("--columns", type=int, default=64)
    p.add_argument("--rows", type=int, default=56)
    p.add_argument("--slices", type=int, default=48)
    p.add_argument("--spacing", type=float, nargs=3, default=[2.0, 2.0, 2.5])
    p.add_argument("--radius", type=float, default=30.0)
    p.add_argument("--centre", type=float, nargs=3, default=[10.0, 20.0, 30.0])
    p.add_argument("--prefix", default="IM", help="file names PREFIX0000.dcm, ...")
    a = p.parse_args()
    os.makedirs(a.dir, exist_ok=True)
    dx, dy, dz = a.spacing
    # The box centred on the ball's centre.
    x0 = a.centre[0] - dx * (a.columns - 1) / 2
    y0 = a.centre[1] - dy * (a.rows - 1) / 2
    z0 = a.centre[2] - dz * (a.slices - 1) / 2
    study, series, frame = generate_uid(), generate_uid(), generate_uid()
    order = list(range(a.slices))
    random.Random(3).shuffle(order)
    for n, k in enumerate(order):
        meta = FileMetaDataset()
        meta.MediaStorageSOPClassUID = MR_IMAGE_STORAGE
        meta.MediaStorageSOPInstanceUID = generate_uid()
        meta.TransferSyntaxUID = ExplicitVRLittleEndian
        path = os.path.join(a.dir, "%s%04d.dcm" % (a.prefix, n))
        ds = FileDataset(path, {}, file_meta=meta, preamble=b"\0" * 128)
        ds.is_little_endian = True
        ds.is_implicit_VR = False
        ds.SOPClassUID = MR_IMAGE_STORAGE
        ds.SOPInstanceUID = meta.MediaStorageSOPInstanceUID
        ds.StudyInstanceUID = study
        ds.SeriesInstanceUID = series
        ds.FrameOfReferenceUID = frame
        ds.Modality = "MR"
        ds.PatientName = "Test^Ball"
        ds.PatientID = "ball"
        ds.SeriesNumber = 1
        ds.InstanceNumber = k + 1
        ds.ImageOrientationPatient = [1, 0, 0, 0, 1, 0]
        ds.ImagePositionPatient = [x0, y0, z0 + k * dz]
        ds.PixelSpacing = [dy, dx]  # row spacing, column spacing
        ds.SliceThickness = dz
        ds.Rows, ds.Columns = a.rows, a.columns
        ds.SamplesPerPixel = 1
        ds.PhotometricInterpretation = "MONOCHROME2"
        ds.BitsAllocated, ds.BitsStored, ds.HighBit = 16, 16, 15
        ds.PixelRepresentation = 0
        z = z0 + k * dz
        pixels = bytearray()
        for j in range(a.rows):
            y = y0 + j * dy
            for i in range(a.columns):
                x = x0 + i * dx
                r = math.dist((x, y, z), a.centre)
                value = 1000 if r < a.radius else 50
                pixels += value.to_bytes(2, "little")
        ds.PixelData = bytes(pixels)
        ds.save_as(path, write_like_original=False)


if __name__ == "__main__":
    main()
