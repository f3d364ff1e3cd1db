<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="en">
<context>
    <name>HamtaProvider</name>
    <message>
        <location filename="../processing/provider.py" line="21"/>
        <source>Hamta</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/provider.py" line="24"/>
        <source>Hamta automatic georeferencing</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>RegisterAlgorithm</name>
    <message>
        <location filename="../processing/register_algorithm.py" line="22"/>
        <source>Similarity (Helmert)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="22"/>
        <source>Affine (polynomial 1)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="22"/>
        <source>Projective</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="22"/>
        <source>Polynomial 2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="22"/>
        <source>Polynomial 3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="22"/>
        <source>Thin plate spline</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="30"/>
        <source>Nearest neighbour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="30"/>
        <source>Bilinear</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="30"/>
        <source>Cubic</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="30"/>
        <source>Cubic B-spline</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="30"/>
        <source>Lanczos</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="37"/>
        <source>Automatic</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="37"/>
        <source>Reference pixel grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="37"/>
        <source>Target&apos;s native resolution</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="42"/>
        <source>Automatic (when images were decimated)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="42"/>
        <source>Always</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="42"/>
        <source>Never</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="47"/>
        <source>Use when it overlaps the reference</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="47"/>
        <source>Always use (fail otherwise)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="47"/>
        <source>Ignore</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="87"/>
        <source>Registration</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="96"/>
        <source>georeference,coregistration,registration,GCP,match,align,warp</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="101"/>
        <source>Target raster (to georeference)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="102"/>
        <source>Reference raster</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="104"/>
        <source>Transformation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="107"/>
        <source>Resampling</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="109"/>
        <source>Target band to match (empty: luminance of RGB, else band 1)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="112"/>
        <source>Reference band to match</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="115"/>
        <source>Target&apos;s own georeferencing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="118"/>
        <source>Output pixel grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="120"/>
        <source>Full-resolution refinement</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="123"/>
        <source>Working image size (pixels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="126"/>
        <source>RANSAC tolerance (working pixels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="129"/>
        <source>Maximum number of GCPs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="132"/>
        <source>Random seed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="137"/>
        <source>Georeferenced raster</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="138"/>
        <source>GCP points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="140"/>
        <source>GCP file for the QGIS Georeferencer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="140"/>
        <source>GCP points (*.points)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="143"/>
        <source>Target with GCPs, not resampled (VRT)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="143"/>
        <source>VRT (*.vrt)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="146"/>
        <source>Report</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="146"/>
        <source>JSON (*.json)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="148"/>
        <source>RMSE of the GCPs (reference pixels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="149"/>
        <source>Leave-one-out RMS (reference pixels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="150"/>
        <source>Number of GCPs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="176"/>
        <source>{} must be a raster file GDAL can read, not a &apos;{}&apos; layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="220"/>
        <source>GCP points must be written to a GeoPackage (.gpkg) file.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="238"/>
        <source>Registration canceled; no outputs were written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="242"/>
        <source>{} GCPs from {} matches; RMSE {:.3f} px, leave-one-out RMS {} px.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="254"/>
        <source>Register raster (SIFT baseline)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="255"/>
        <source>Registers the target raster onto the reference raster automatically: OpenCV SIFT keypoints, Lowe&apos;s ratio test with a mutual check, seeded RANSAC, full-resolution refinement, and the chosen transformation fitted on well-spread GCPs. Writes the georeferenced raster, the GCPs as a point layer and, on request, a QGIS Georeferencer .points file, a VRT carrying the GCPs and a JSON report.&lt;br&gt;&lt;br&gt;Reference: D. G. Lowe (2004), Distinctive image features from scale-invariant keypoints, IJCV 60(2):91-110, doi:10.1023/B:VISI.0000029664.99615.94</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="268"/>
        <source>Register satellite image (RILBP, rotation-invariant)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="269"/>
        <source>Registers an optical satellite image onto a reference with any rotation between them: CenSurE octagon keypoints described by the rotation-invariant LBP descriptor (rings, intensity-order sub-regions, centre-symmetric LBP in each pixel&apos;s radial frame; no orientation step), mutual ratio-test matching, seeded RANSAC and the chosen transformation fitted on well-spread GCPs. Product defaults add sub-pixel keypoints and smoothed, radius-2 codes; the CLI method &apos;rilbp-faithful&apos; is the paper as written.&lt;br&gt;&lt;br&gt;Reference: A. Sedaghat and N. Mohammadi (2019), Rotation invariant local binary pattern descriptor for remote sensing image matching, Journal of Geospatial Information Technology 7(2):223-239; M. Agrawal, K. Konolige and M. R. Blas (2008), CenSurE, ECCV.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="284"/>
        <source>Register aerial image onto satellite image (SIBRIF, fast)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="285"/>
        <source>Registers an aerial (or any optical) image onto a satellite reference quickly: SIFT difference-of-Gaussian keypoints detected on a thresholded Sobel edge image, rBRIEF binary descriptors steered by the intensity centroid, removal of self-similar keypoints, mutual Hamming matching and RANSAC with affine samples. Few, strong keypoints make it several times faster than SIFT. Product defaults describe each keypoint at its own scale and add a ratio test; the CLI method &apos;sibrif-faithful&apos; is the paper as written.&lt;br&gt;&lt;br&gt;Reference: M. Safdari, P. Moallem and M. Sattari, Robust and fast aerial and satellite image matching based on selective scale and rotation (SIBRIF).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="299"/>
        <source>Register SAR image onto SAR image (ND-SIFT + phase congruency)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="301"/>
        <source>Registers a SAR image onto a SAR reference (another date, band or polarisation) despite speckle: a nonlinear diffusion scale space whose conductance uses the speckle-robust ROEWA gradient, SIFT keypoints and descriptors on it, keypoints kept only where phase congruency shows real structure, ratio-test matching, seeded RANSAC, then correlation refinement on a grid at full resolution. Set what the rasters hold (amplitude, intensity or dB; complex data is read as amplitude). Product defaults pre-smooth and use a one-way ratio test; the CLI method &apos;ndsift-pc-faithful&apos; is the paper as written.&lt;br&gt;&lt;br&gt;Reference: J. Fan, Y. Wu, F. Wang, Q. Zhang, G. Liao and M. Li (2015), SAR image registration using phase congruency and nonlinear diffusion-based SIFT, IEEE Geoscience and Remote Sensing Letters 12(3):562-566, doi:10.1109/LGRS.2014.2351396</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="317"/>
        <source>Register SAR image onto optical image</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="318"/>
        <source>Registers a SAR image (the target) onto an optical reference, where intensities do not correspond and contrast is often inverted: an exhaustive search over rotation (up to 30 degrees either way), scale (up to 2 times either way) and shift on CFOG structural descriptors (gradient orientations, blind to the sign of contrast), then CFOG template matching on a regular grid, seeded RANSAC, the chosen transformation on well-spread GCPs, and full-resolution refinement of decimated images with the same similarity. Widen the rotation range for targets that are not roughly north-up. The CLI method &apos;lines-spectral-faithful&apos; is the thesis&apos;s line-intersection matcher as written (Radon lines, eigenvector and Voronoi/Hausdorff spectral matching), which rarely finds enough correct matches to register.&lt;br&gt;&lt;br&gt;References: S. Gholami (2018), Automatic registration of SAR images onto optical images, M.Sc. thesis, Shahrood University of Technology; Y. Ye, L. Bruzzone, J. Shan, F. Bovolo and Q. Zhu (2019), Fast and robust matching for multimodal remote sensing image registration, IEEE Transactions on Geoscience and Remote Sensing 57(11):9059-9070, doi:10.1109/TGRS.2019.2924684</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>
