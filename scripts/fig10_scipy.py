#!/usr/bin/python3
"""scipy's cubic B-spline interpolation of a Cartesian subsample against the MRI template, for
docs/fig10.md's interpolation table (scripts/fig10.sh runs it): the row `boxrecon compare` prints
for boxgen's filters, measured the same way (the template's voxels inside the box, PSNR's peak
the template's range, the mask of voxels above 20).

scipy.ndimage.map_coordinates(order=3, prefilter=True, mode='mirror') interpolates the subsample
(a Cartesian NRRD that `boxrecon subsample` wrote, read with the boxgen module) at the world
positions of the template's voxels (nibabel reads the template and its affine, which must be
axis-aligned).

Usage: /usr/bin/python3 scripts/fig10_scipy.py TEMPLATE.nii.gz SUBSAMPLE.nrrd X0 Y0 Z0 X1 Y1 Z1
prints: RMS PSNR RMS_MASKED PSNR_MASKED POINTS
"""
import sys

import nibabel
import numpy as np
import scipy.ndimage as ndimage

import boxgen


def main():
    template, subsample = sys.argv[1], sys.argv[2]
    lo = np.array([float(x) for x in sys.argv[3:6]])
    hi = np.array([float(x) for x in sys.argv[6:9]])
    image = nibabel.load(template)
    affine = image.affine
    if np.count_nonzero(affine[:3, :3] - np.diag(np.diag(affine[:3, :3]))) or np.any(
            np.diag(affine[:3, :3]) <= 0):
        raise SystemExit("the template's affine is not axis-aligned with positive spacings")
    reference = np.asarray(image.dataobj, dtype=np.float64)
    peak = float(reference.max() - reference.min())
    step, origin = np.diag(affine[:3, :3]), affine[:3, 3]
    # The voxels whose world positions lie in the box, per axis.
    ranges = []
    for a in range(3):
        first = int(np.ceil((lo[a] - origin[a]) / step[a] - 1e-9))
        last = int(np.floor((hi[a] - origin[a]) / step[a] + 1e-9))
        ranges.append(np.arange(max(first, 0), min(last, reference.shape[a] - 1) + 1))
    volume = boxgen.read_volume(subsample)
    if volume.lattice != "cartesian":
        raise SystemExit("the subsample must be Cartesian")
    # The prefilter once, on the whole subsample (what map_coordinates(prefilter=True) does on
    # each call); then each slice of points is interpolated from the coefficients.
    coefficients = ndimage.spline_filter(np.asarray(volume.samples[0], dtype=np.float64), order=3,
                                         mode="mirror")
    spacing = np.broadcast_to(np.asarray(volume.spacing, dtype=np.float64), (3,))
    sub_origin = np.asarray(volume.origin, dtype=np.float64)
    squares = masked = 0.0
    count = masked_count = 0
    for k in ranges[2]:  # one slice at a time: the box holds about 19 million voxels
        i, j = np.meshgrid(ranges[0], ranges[1], indexing="ij")
        world = [origin[0] + step[0] * i, origin[1] + step[1] * j,
                 np.full(i.shape, origin[2] + step[2] * k)]
        coordinates = [(world[a] - sub_origin[a]) / spacing[a] for a in range(3)]
        values = ndimage.map_coordinates(coefficients, coordinates, order=3, prefilter=False,
                                         mode="mirror")
        truth = reference[np.ix_(ranges[0], ranges[1], [k])][:, :, 0]
        error = values - truth
        squares += float(np.sum(error ** 2))
        count += error.size
        mask = truth > 20
        masked += float(np.sum(error[mask] ** 2))
        masked_count += int(mask.sum())
    rms, rms_masked = np.sqrt(squares / count), np.sqrt(masked / masked_count)
    print(f"{rms:.4f} {20 * np.log10(peak / rms):.3f} {rms_masked:.4f} "
          f"{20 * np.log10(peak / rms_masked):.3f} {count}")


if __name__ == "__main__":
    main()
