<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="en">
<context>
    <name>@default</name>
    <message>
        <location filename="../plugin/action.py" line="50"/>
        <source>Hamta cannot run: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="60"/>
        <source>The reference layer &apos;{}&apos; could not be read ({}: {}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="63"/>
        <source>Auto-georeference &apos;{}&apos;</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="102"/>
        <source>Auto-georeference of &apos;{}&apos; canceled; nothing was added.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="107"/>
        <source>Open the GCPs in the Georeferencer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="122"/>
        <source>Hamta stopped on an unexpected error ({}: {}); nothing was added. Please report it (the details are in the message log).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="147"/>
        <source>{} (georeferenced)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="149"/>
        <source>{} GCPs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="154"/>
        <source>The output &apos;{}&apos; could not be loaded.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="178"/>
        <source>Open report</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="187"/>
        <source>In the Georeferencer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="187"/>
        <source>In Raster ▸ Georeferencer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="188"/>
        <source>{}, open the raster '{}' (File ▸ Open Raster…), then File ▸ Load GCP Points… and paste the path of the GCP file, now on the clipboard: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="275"/>
        <source>Auto-georeference</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="127"/>
        <source>The raster file to georeference (a raster layer read by GDAL).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="128"/>
        <source>Target raster</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="139"/>
        <source>Reference layer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="154"/>
        <source>On by default for a target without georeferencing (the map canvas extent). On for a georeferenced target, Hamta ignores the target&apos;s georeferencing and searches here.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="164"/>
        <source>Search area, {} (where to look for the target)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="168"/>
        <source>A folder for the warped raster, the GCPs (GeoPackage and .points) and the reports; files of an earlier run there are replaced.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="171"/>
        <source>Write the georeferenced raster even when the independent check does not confirm the result (it is then marked NOT VERIFIED).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="173"/>
        <source>Output folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="177"/>
        <source>Run</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="250"/>
        <source>Choose the raster to georeference (add it to the project first).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="258"/>
        <source>Choose a reference layer other than the target: a basemap or a georeferenced raster.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="264"/>
        <source>Choose an output folder.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="267"/>
        <source>&apos;{}&apos; has no georeferencing: turn on the search area (the map canvas extent by default) so that Hamta knows where to look in &apos;{}&apos;.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="80"/>
        <source>Cancel</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="75"/>
        <source>Auto-georeference &apos;{}&apos;: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="117"/>
        <source>Details</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="257"/>
        <source>&apos;{}&apos; onto &apos;{}&apos;</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="269"/>
        <source>Method: {}; {} GCPs; transformation: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="273"/>
        <source>Time: {:.1f} s</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="76"/>
        <source>starting</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="113"/>
        <source>Keep anyway</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="135"/>
        <source>Keep &apos;{}&apos; (not verified)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="139"/>
        <source>Keeping &apos;{}&apos;: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="225"/>
        <source>{:.1f} m on the ground</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="225"/>
        <source>{:.2f} m on the ground</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="228"/>
        <source>{:.1f} px of &apos;{}&apos;</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="267"/>
        <source>What may help:</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="275"/>
        <source>Kept after the run: the outputs were written in {:.1f} s.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="286"/>
        <source>&apos;Keep anyway&apos; here, or &apos;{}&apos; in the dialog: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="289"/>
        <source>Search area</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="170"/>
        <source>Keep unverified results</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="114"/>
        <source>&apos;{}&apos; not verified; nothing added.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="147"/>
        <source>NOT VERIFIED {} (georeferenced)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="170"/>
        <source>&apos;{}&apos; verified{}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="170"/>
        <source>, within {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="171"/>
        <source>&apos;{}&apos; NOT VERIFIED; check it before use.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="258"/>
        <source>&apos;{}&apos; by its own printed grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="197"/>
        <source>By the sheet&apos;s own grid (no reference layer)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="203"/>
        <source>The sheet&apos;s projection: the results are in it (sheets rarely print it).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="204"/>
        <source>CRS of the sheet</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="206"/>
        <source>GCP points (*.points)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="211"/>
        <source>Hints (.points)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="253"/>
        <source>Choose the CRS of the sheet, or a reference layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="208"/>
        <source>Two or three crossings of the printed lines placed roughly in the Georeferencer with their coordinates as printed, saved as GCP points; empty: the labels printed in the sheet&apos;s margins are read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="255"/>
        <source>The hints file does not exist: choose the GCP points (.points) saved in the Georeferencer, or leave it empty to have the sheet&apos;s printed labels read.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="201"/>
        <source>choose the sheet&apos;s projection</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="207"/>
        <source>empty: the coordinates printed in the margins are read</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="135"/>
        <source>The georeferenced layer to match the target on: a basemap (XYZ tiles, WMS, WMTS...), a raster, or a layer of areas or lines (water, buildings, roads: for a scanned map). The results are in its CRS. None: a scanned map is georeferenced by the grid printed on it.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="118"/>
        <source>&apos;{}&apos; not georeferenced; nothing added.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="260"/>
        <source>Independent check: {}; {}; error within {} (tolerance {})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="260"/>
        <source>&apos;{}&apos; has no georeferencing, so it cannot be the reference: choose a basemap or a georeferenced raster, or no reference layer to georeference &apos;{}&apos; by its printed grid.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>AutoGeoreference</name>
    <message>
        <location filename="../plugin/plugin.py" line="61"/>
        <source>Auto-georeference…</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../plugin/plugin.py" line="64"/>
        <source>Georeference the selected raster layer on the visible basemap (Hamta)</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>BatchRegisterAlgorithm</name>
    <message>
        <location filename="../processing/catalogue.py" line="32"/>
        <source>Batch register</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="63"/>
        <source>Registration</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="87"/>
        <source>Target rasters</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="89"/>
        <source>Reference raster (for the targets above)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="91"/>
        <source>Job lists (*.csv *.gpkg)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="102"/>
        <source>Method</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="104"/>
        <source>Keep unverified results</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="112"/>
        <source>Workers of the local cluster (0: one per CPU)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="115"/>
        <source>Output folder</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="116"/>
        <source>Batch results (footprints)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="163"/>
        <source>Batch stopped on an unexpected error ({}: {}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="110"/>
        <source>Dask scheduler (tls://host:port; empty: a local cluster)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="91"/>
        <source>Job list instead (CSV or GeoPackage)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="108"/>
        <source>Dask scheduler (tls://host:port)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="137"/>
        <source>The reference layer &apos;{}&apos; ({}) cannot be read by every pair of a batch: use a raster file, an XYZ or WMS layer, or save the layer&apos;s area as a GeoTIFF first.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="72"/>
        <source>Registers many targets in one run: the rasters chosen as targets onto one reference, or every row of a job list (CSV or GeoPackage with columns target, reference, method, model, output). Pairs run in parallel on Dask: a local cluster of threads inside QGIS (reachable only with TLS credentials made for the run), or an existing scheduler given as tls://host:port, with the certificates of Dask&apos;s configuration (distributed.comm.tls.*; tcp:// works but is unauthenticated). Each pair writes its outputs into its own folder under the output folder (a job list&apos;s output: a folder inside it); a pair that fails is recorded and the others go on; running again skips the pairs already done. The result layer holds every target&apos;s footprint with its verdict, error figures, method, time and output paths.

Scanned sheets of a map series: choose no reference but the CRS of their printed coordinates; each sheet is georeferenced by its own printed grid (its labels read, or the hints of the Georeferencer&apos;s &apos;&lt;raster&gt;.points&apos; beside it); a job list does the same with its &apos;crs&apos; and &apos;hints&apos; columns.

QGIS&apos;s own batch mode over the single-pair algorithms works too.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="93"/>
        <source>Job list instead (CSV or GeoPackage: target, reference, method, model, crs, hints, output)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="96"/>
        <source>CRS of printed coordinates (sheets)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="98"/>
        <source>Scanned sheets georeferenced by their own printed grid: what their printed coordinates count in (EPSG:4326 or EPSG:4269 for degrees, the national grid&apos;s CRS for its metres, feet or yards)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="132"/>
        <source>Choose target rasters and a reference raster (or, for scanned sheets by their printed grid, the CRS of their printed coordinates), or a job list.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>GridAlgorithm</name>
    <message>
        <location filename="../processing/grid_algorithm.py" line="50"/>
        <source>georeference,scanned map,grid,graticule,sheet,GCP,crossings</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="53"/>
        <source>Scanned map (to georeference)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="65"/>
        <source>Keep unverified results</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="73"/>
        <source>Grid step (printed units)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="54"/>
        <source>CRS of the printed coordinates</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="59"/>
        <source>Hints: crossings placed (.points)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="55"/>
        <source>What the coordinates printed on the sheet count in: EPSG:4326 or EPSG:4269 for degrees of a graticule (whatever projection it is drawn in: it is found), the national grid&apos;s CRS for its metres, feet or yards</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="61"/>
        <source>Two or three crossings of the printed lines placed roughly in the QGIS Georeferencer, with their coordinates as printed (degrees, or the grid&apos;s units), saved as GCP points (empty: the labels printed in the sheet&apos;s margins are read by OCR)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="75"/>
        <source>The step of the printed grid, in its coordinates (empty: the largest usual step the hints or labels fit whose lines are printed)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="83"/>
        <source>Choose the CRS of the printed coordinates.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>HamtaPlugin</name>
    <message>
        <location filename="../plugin/plugin.py" line="54"/>
        <source>its algorithms cannot run; press &apos;More&apos; for why and how to fix it.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>HamtaProvider</name>
    <message>
        <location filename="../processing/provider.py" line="148"/>
        <source>Hamta</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/provider.py" line="151"/>
        <source>Hamta automatic georeferencing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/provider.py" line="114"/>
        <source>{} (unavailable: {})</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/provider.py" line="163"/>
        <source>Hamta cannot run ({}): see the algorithm&apos;s help for how to fix it.</source>
        <translation type="unfinished"></translation>
    </message>
</context>
<context>
    <name>RegisterAlgorithm</name>
    <message>
        <location filename="core_strings.py" line="7"/>
        <source>Similarity (Helmert)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="8"/>
        <source>Affine (polynomial 1)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="9"/>
        <source>Projective</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="10"/>
        <source>Polynomial 2</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="11"/>
        <source>Polynomial 3</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="12"/>
        <source>Thin plate spline</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="65"/>
        <source>Nearest neighbour</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="66"/>
        <source>Bilinear</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="67"/>
        <source>Cubic</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="68"/>
        <source>Cubic B-spline</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="69"/>
        <source>Lanczos</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="79"/>
        <source>Automatic</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="80"/>
        <source>Reference pixel grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="81"/>
        <source>Target&apos;s native resolution</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="24"/>
        <source>Automatic (when images were decimated)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="25"/>
        <source>Always</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="26"/>
        <source>Never</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="39"/>
        <source>Use when it overlaps the reference</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="40"/>
        <source>Always use (fail otherwise)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="41"/>
        <source>Ignore</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="113"/>
        <source>Registration</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="128"/>
        <source>georeference,coregistration,registration,GCP,match,align,warp</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="135"/>
        <source>Target raster (to georeference)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="4"/>
        <source>Transformation</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="63"/>
        <source>Resampling</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="45"/>
        <source>Reference band to match</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="37"/>
        <source>Target&apos;s own georeferencing</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="77"/>
        <source>Output pixel grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="22"/>
        <source>Full-resolution refinement</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="15"/>
        <source>Working image size (pixels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="27"/>
        <source>Maximum number of GCPs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="20"/>
        <source>Random seed</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="150"/>
        <source>Georeferenced raster</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="151"/>
        <source>GCP points</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="153"/>
        <source>GCP file for the QGIS Georeferencer</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="153"/>
        <source>GCP points (*.points)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="156"/>
        <source>Target with GCPs, not resampled (VRT)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="156"/>
        <source>VRT (*.vrt)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="159"/>
        <source>Report</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="159"/>
        <source>JSON (*.json)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="166"/>
        <source>RMSE of the GCPs (reference pixels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="167"/>
        <source>Leave-one-out RMS (reference pixels)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="168"/>
        <source>Number of GCPs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="198"/>
        <source>{} must be a raster file GDAL can read, not a &apos;{}&apos; layer.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="269"/>
        <source>Registration canceled; no outputs were written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="229"/>
        <source>Register raster (SIFT baseline)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="147"/>
        <source>Register satellite image (RILBP, rotation-invariant)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="165"/>
        <source>Register aerial image onto satellite image (SIBRIF, fast)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="118"/>
        <source>Register SAR image onto SAR image (ND-SIFT + phase congruency)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="104"/>
        <source>Register SAR image onto optical image</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="164"/>
        <source>Verdict of the independent check</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="165"/>
        <source>Method that produced the result</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="276"/>
        <source>The registration was not verified: {}. No georeferenced output was written; set &apos;Keep unverified results&apos; to write it anyway.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="339"/>
        <source>NOT VERIFIED ({}): {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/catalogue.py" line="21"/>
        <source>Register raster (automatic)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/catalogue.py" line="21"/>
        <source>Registers the target raster onto the reference raster and chooses the method itself: the fast SIFT matcher first, then matchers for images of different modality (SAR, infrared, maps) and for SAR, until a result passes an independent check. The check compares the two rasters at sites spread over the overlap, not the matches the model was fitted on, against what wrong alignments of the same rasters give, and bounds the remaining error. A result that does not verify is not written unless &apos;Keep unverified results&apos; is set; the log lists every method tried, its verdict and its time. The other algorithms of this group run one method each, for experts.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="177"/>
        <source>Register across modalities at any rotation and scale</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="195"/>
        <source>What the SAR (target) raster holds: amplitude, intensity or db.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="196"/>
        <source>Lee speckle filter on the SAR image (the thesis).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="197"/>
        <source>Lee window side, px (not given; 7).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="198"/>
        <source>Equivalent number of looks of the SAR image (not given; 1).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="199"/>
        <source>GGS window shape alpha (Shui &amp; Cheng&apos;s practical setting).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="200"/>
        <source>GGS window width beta, px.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="201"/>
        <source>GGS window length sigma_x, px (l_f = 13).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="202"/>
        <source>GGS orientations P (not given; 8).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="203"/>
        <source>Hysteresis low threshold on 1 - ratio (not given).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="204"/>
        <source>Hysteresis high threshold on 1 - ratio (not given).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="205"/>
        <source>Edge components smaller than this are removed (the thesis: 65).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="206"/>
        <source>Radon peaks taken before clustering (not given; 40).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="207"/>
        <source>Radon angle step, degrees (MATLAB&apos;s default 1).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="208"/>
        <source>Fewest edge pixels on a line; 0 = Sui et al.&apos;s 15 px per 256 px of image side.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="209"/>
        <source>Lines closer than this in angle ... (not given; 5).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="210"/>
        <source>... and this in offset are one line (not given; 10).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="211"/>
        <source>Line pairs crossing at less than this are not intersected (Sui et al.).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="235"/>
        <source>Eigenvector matching, VSPM, or their fusion (the thesis).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="213"/>
        <source>Fusion rule (not given): score-level sum, or cascade (VSPM&apos;s proximity inside eigenvector matching).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="214"/>
        <source>Weight of the eigenvector score in the score-level fusion.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="215"/>
        <source>Eigenvector proximity sigma as a fraction of each point set&apos;s RMS spread (not given).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="216"/>
        <source>VSPM proximity matrix: as printed (eq. 2-73), laplacian or gaussian.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="217"/>
        <source>Crossing angles of matched intersections differ by less (the thesis).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="212"/>
        <source>Shapiro-Brady eigenvector matching alone (the thesis&apos;s baseline).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="218"/>
        <source>VSPM alone (the thesis&apos;s baseline).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="106"/>
        <source>What the target raster holds when it is SAR: amplitude, intensity or db (other images: leave amplitude).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="107"/>
        <source>No Lee filter: CFOG&apos;s smoothing already averages speckle, and the filter measured no gain (multimodal proxy 8/8 either way; real pairs 0.85 vs 1.06 px median).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="108"/>
        <source>Coarse transform: exhaustive CFOG search (default: it registers where the thesis&apos;s 5-8 matches cannot) or the thesis&apos;s lines.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="109"/>
        <source>Rotations searched, +- degrees (georeferenced targets arrive north-up, so rotation is small).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="110"/>
        <source>Scales searched, 1/max_scale .. max_scale (2 registers the scale family&apos;s 0.5-2, 10/10 against 6/10 for 1.5, for 26 % more time on a 1000 px pair).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="111"/>
        <source>Longest reference side at the first search level, px.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="112"/>
        <source>The search compares descriptors minus their local mean over this many first-level px: with the global mean (0) regional orientation statistics favoured wrong axis-aligned candidates (overlap family 8/10; 3 px: 10/10, 6 px: 9/10).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="113"/>
        <source>Side of the CFOG templates, working px.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="114"/>
        <source>Search radius of the first dense pass, working px (covers the coarse error).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="115"/>
        <source>Weakest accepted template correlation; RANSAC removes the rest.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="116"/>
        <source>Templates per dense pass.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="117"/>
        <source>Coarse candidates checked by dense matching when the best is not convincing.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="120"/>
        <source>What the SAR raster holds: amplitude, intensity or db (complex is read as amplitude).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="121"/>
        <source>Scale space: nonlinear (the paper), gaussian or bilateral (baselines).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="122"/>
        <source>Run on log amplitude, where speckle is additive and of one strength everywhere (not in the paper).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="123"/>
        <source>Gaussian pre-smoothing to sigma_0 before the diffusion, as KAZE does: on 1-look speckle it turns 3 of 24 failures into successes (the paper starts from the original image).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="124"/>
        <source>Octaves O (the paper: 4).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="125"/>
        <source>Sub-levels S per octave (the paper: 3; S + 3 images per octave).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="126"/>
        <source>Base scale sigma_0 (gap; Lowe&apos;s 1.6).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="127"/>
        <source>ROEWA exponential weight alpha (gap; SAR-SIFT&apos;s 2).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="128"/>
        <source>Contrast factor K = this percentile of the ROEWA gradient (gap; KAZE&apos;s 70).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="129"/>
        <source>K is multiplied by this at each new octave (the paper: &apos;change K&apos;; AKAZE&apos;s 0.75).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="130"/>
        <source>Gradient inside the conductance: roewa (the paper) or difference.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="131"/>
        <source>DoG contrast threshold on the [0, 1] amplitude (gap; Lowe&apos;s 0.03).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="132"/>
        <source>DoG edge ratio r (Lowe&apos;s 10).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="133"/>
        <source>Drop keypoints whose phase congruency is below pc_threshold (the paper).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="134"/>
        <source>Phase congruency threshold (the paper: 0.01).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="135"/>
        <source>Kovesi&apos;s noise multiplier k (gap; his default 2).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="136"/>
        <source>Range sigma of the bilateral scale space on the [0, 1] amplitude (BFSIFT baseline; not given).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="137"/>
        <source>Ignore keypoints of the finest octave (BFSIFT does).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="138"/>
        <source>Nearest/second-nearest ratio (the paper: 0.8).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="139"/>
        <source>One-way ratio test: dual ratio matching keeps too few matches on 1-look speckle, and RANSAC removes the extra outliers (the paper: dual-ratio).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="188"/>
        <source>Gaussian pre-smoothing to sigma_0 before the diffusion, as KAZE does (the paper starts from the original image).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="191"/>
        <source>Dual matching: both directions pass the ratio test (the paper).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="219"/>
        <source>NDSS+SIFT: the paper&apos;s ablation without phase congruency.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="193"/>
        <source>Gaussian scale space (the paper&apos;s SIFT baseline).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="194"/>
        <source>No phase congruency in the baseline.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="187"/>
        <source>Bilateral-filter scale space (BFSIFT).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="189"/>
        <source>No phase congruency in BFSIFT.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="190"/>
        <source>BFSIFT skips the finest scale.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="220"/>
        <source>Strongest keypoints kept per image.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="221"/>
        <source>FAST corner threshold (OpenCV default).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="222"/>
        <source>Pyramid levels, scale factor 1.2 (OpenCV default).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="223"/>
        <source>Nearest/second-nearest Hamming distance ratio.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="155"/>
        <source>Cross-check of matches: none, mutual or dual-ratio.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="224"/>
        <source>Strongest SIFT keypoints kept per image (0 = all).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="225"/>
        <source>Nearest/second-nearest distance ratio (as the SIFT baseline).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="226"/>
        <source>Correspondences per side of the grid that carries the shift.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="227"/>
        <source>Lowest accepted normalised correlation peak.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="228"/>
        <source>Strongest FAST corners kept per image (RIFT: 5000).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="149"/>
        <source>Strongest CenSurE keypoints kept per image (the paper: 2500).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="150"/>
        <source>Smallest |CenSurE response| in grey levels (gap: paper uses CenSurE defaults without values).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="151"/>
        <source>CenSurE&apos;s edge test limit on trace^2/det (Agrawal et al. 2008).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="152"/>
        <source>Region radius = factor x half the outer octagon (gap in the paper).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="153"/>
        <source>Product: quadratic sub-pixel keypoint positions (CenSurE keeps whole pixels).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="154"/>
        <source>Nearest/second-nearest distance ratio (gap: the paper&apos;s rule is not given).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="156"/>
        <source>LBP neighbour radius in region pixels (gap; the paper&apos;s figure shows 1; 2 keeps codes stable under keypoint and resampling jitter).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="157"/>
        <source>Product: Gaussian sigma (region pixels) before coding; the paper has none, and radius-1 codes on raw pixels flip on sensor noise.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="158"/>
        <source>CS-LBP threshold T in grey levels (gap; 0 = exact gain/offset invariance).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="159"/>
        <source>Ring weight: literal 1-(d/h)^2 (the paper) or border 1-(2d/h)^2.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="236"/>
        <source>Faithful: whole-pixel CenSurE positions, as the paper.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="237"/>
        <source>Faithful: radius 1, the paper&apos;s Fig. 1.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="238"/>
        <source>Faithful: no smoothing, as the paper.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="192"/>
        <source>Faithful: whole-pixel CenSurE positions, as in the paper&apos;s comparison.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="167"/>
        <source>Sobel magnitude threshold T (0..255; gap in the paper, default from a sweep).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="168"/>
        <source>Hamming distance under which a keypoint with a near-duplicate in its own image is removed (gap; from a sweep).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="169"/>
        <source>Gradient magnitude: l1 = 0.5|Gx|+0.5|Gy| (OpenCV tutorial, the spec&apos;s reading) or l2 = sqrt(Gx^2+Gy^2)/sqrt(2), which does not change with edge direction.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="170"/>
        <source>to-zero keeps magnitudes above T (the paper); soft subtracts T, so the edge image has no jumps at the threshold for the DoG to fire on.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="171"/>
        <source>Resolution at which the DoG pyramid starts (2 = OpenCV SIFT&apos;s upsampled base, the paper&apos;s; 1 = full resolution, 4x less work).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="172"/>
        <source>Strongest DoG keypoints kept per image (0 = all, as the paper).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="173"/>
        <source>SIFT DoG contrast threshold on the edge image (OpenCV default).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="174"/>
        <source>Describe each keypoint on the pyramid level matching its SIFT size (the paper uses a fixed 31-px patch, which breaks beyond ~1.5x scale).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="175"/>
        <source>Lowe ratio on Hamming distances (1 = off, as the paper).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="176"/>
        <source>Spec Appendix B (not in the paper): keep matches at the peaks of the angle and log-scale difference histograms.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="239"/>
        <source>Faithful: OpenCV tutorial magnitude 0.5|Gx|+0.5|Gy|.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="240"/>
        <source>Faithful: threshold-to-zero.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="241"/>
        <source>Faithful: OpenCV SIFT as is (upsampled base).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="242"/>
        <source>Faithful: every DoG keypoint.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="243"/>
        <source>Faithful: one 31-px patch at full resolution for every keypoint.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="244"/>
        <source>Faithful: mutual nearest neighbours without a ratio test.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="231"/>
        <source>Strongest keypoints kept per image (0 = all).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="232"/>
        <source>DoG contrast threshold (OpenCV default, Lowe 2004).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="233"/>
        <source>Edge-response ratio limit (Lowe 2004).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="234"/>
        <source>Lowe&apos;s nearest/second-nearest distance ratio.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="179"/>
        <source>Longest reference side for feature extraction, px: enough detail for RIFT features, and their cost.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="180"/>
        <source>Pyramid levels (factors 2^-k/2) per image; 3 covers scales 1/2 to 2.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="181"/>
        <source>Keypoints kept at the first level (0.7 and 0.5 times that at the next two).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="182"/>
        <source>Rotation-scale hypotheses checked densely (10 gave nothing more).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="183"/>
        <source>Hypotheses refined by local RIFT (5 gave nothing more).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="184"/>
        <source>Longest reference side for the dense check, px: keeps its 30 FFT trials per hypothesis cheap; where CFOG separated right from wrong poses best.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="185"/>
        <source>Longest reference side for local RIFT matching, px.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="186"/>
        <source>Fewest local-RIFT inliers for a refined hypothesis.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="86"/>
        <source>Output CRS (empty: the reference&apos;s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="89"/>
        <source>Output format</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="97"/>
        <source>Pixels outside the target</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="161"/>
        <source>HTML files (*.html)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="260"/>
        <source>GCP points are written to a GeoPackage: choose a .gpkg file (got &apos;{}&apos;).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="282"/>
        <source>Invalid parameter: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="92"/>
        <source>GeoTIFF (tiled, compressed)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="94"/>
        <source>Warped VRT (no pixels copied)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="100"/>
        <source>Alpha band</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="101"/>
        <source>Nodata value</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="91"/>
        <source>From the file name (.vrt or GeoTIFF)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="93"/>
        <source>Cloud-optimised GeoTIFF</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="99"/>
        <source>Automatic (nodata, NaN or an alpha band)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="13"/>
        <source>Linear (scale and shift per axis)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="71"/>
        <source>Mode (most frequent: classes)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="72"/>
        <source>Maximum</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="73"/>
        <source>Minimum</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="74"/>
        <source>Median</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="75"/>
        <source>First quartile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="76"/>
        <source>Third quartile</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="139"/>
        <source>Keep unverified results</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="52"/>
        <source>Local (non-rigid) correction</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="58"/>
        <source>Pixel-to-pixel (reference not georeferenced)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="161"/>
        <source>Quality report (HTML)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="314"/>
        <source>{} (set &apos;{}&apos;).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="347"/>
        <source>{}; self-reported RMSE {:.3f} px, leave-one-out RMS {} px (residuals of the fit, not its accuracy).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="54"/>
        <source>Local window (reference px; 0: automatic)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="47"/>
        <source>Accuracy asked for (reference px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="42"/>
        <source>Target band to match</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="83"/>
        <source>Output pixel size (output CRS units)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="95"/>
        <source>GDAL creation options</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="17"/>
        <source>RANSAC tolerance (working px)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="70"/>
        <source>Average</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="122"/>
        <source>References: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="5"/>
        <source>transform model: similarity, affine, projective, polynomial-2, polynomial-3, tps, linear, auto (the method&apos;s, affine for most, or polynomial-2 where the points bend away from it and the check bounds its error more tightly)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="16"/>
        <source>pixel budget of the images matched (larger rasters are read decimated, then refined at full resolution)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="19"/>
        <source>the method&apos;s, 3 for most</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="21"/>
        <source>seed of every random choice (RANSAC, sampling, inside methods), for reproducible runs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="23"/>
        <source>full-resolution refinement of the matches: auto refines when an image was decimated or the method asks for it</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="28"/>
        <source>most GCPs kept (well spread) for the fit and the outputs</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="29"/>
        <source>Fewest agreeing matches</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="30"/>
        <source>fewest agreeing correspondences accepted as a registration (at least the model&apos;s minimum + 2)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="31"/>
        <source>the method&apos;s</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="32"/>
        <source>Outlier rejection</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="33"/>
        <source>outlier rejection before the fit: ransac, none (fit every correspondence, as some papers do) or triplets (cluster the transforms of match triplets)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="34"/>
        <source>Seeded LO-RANSAC</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="36"/>
        <source>Cluster the transforms of match triplets</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="38"/>
        <source>use the target&apos;s own georeferencing as a starting point (auto: when it overlaps the reference), or ignore it when it is wrong</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="43"/>
        <source>band of the target to match</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="44"/>
        <source>luminance of RGB, else band 1</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="48"/>
        <source>accuracy asked for, reference px: a result is verified only when the independent check bounds its error within this</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="49"/>
        <source>Time cap of &apos;auto&apos; (s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="53"/>
        <source>after the global model, correct local (non-rigid) misalignment from shifts measured on a dense grid of windows; the model becomes a thin plate spline through the grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="55"/>
        <source>local correction window side, reference px (0: automatic, 64 px, or 96 px for methods that correlate structure across modalities; otherwise at least 16)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="64"/>
        <source>resampling of the warped output</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="78"/>
        <source>output pixel grid: the reference&apos;s, the target&apos;s own resolution, auto (the reference&apos;s when the resolutions are within 10 %), or target: the target&apos;s pixels unchanged under a corrected geotransform (where the model is a shift and scale, in the reference CRS)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="84"/>
        <source>output pixel size in output CRS units (overrides the grid&apos;s)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="85"/>
        <source>from the pixel grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="87"/>
        <source>output CRS: EPSG:code, WKT or PROJ string</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="88"/>
        <source>the reference&apos;s CRS</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="96"/>
        <source>GDAL creation options of the warped raster, KEY=VALUE (e.g. COMPRESS=ZSTD, PREDICTOR=2), added to and overriding Hamta&apos;s defaults for the format</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="102"/>
        <source>nodata value with fill &apos;nodata&apos;</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="103"/>
        <source>the target&apos;s, else 0</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="230"/>
        <source>Registers the target raster onto the reference raster automatically: OpenCV SIFT keypoints, Lowe&apos;s ratio test with a mutual check, seeded RANSAC, full-resolution refinement, and the chosen transformation fitted on well-spread GCPs. Writes the georeferenced raster, the GCPs as a point layer and, on request, a QGIS Georeferencer .points file, a VRT carrying the GCPs and a JSON report.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="105"/>
        <source>Registers a SAR image (the target) onto an optical reference, where intensities do not correspond and contrast is often inverted: an exhaustive search over rotation (up to 30 degrees either way), scale (up to 2 times either way) and shift on CFOG structural descriptors (gradient orientations, blind to the sign of contrast), then CFOG template matching on a regular grid, seeded RANSAC, the chosen transformation on well-spread GCPs, and full-resolution refinement of decimated images with the same similarity. Widen the rotation range for targets that are not roughly north-up. The CLI method &apos;lines-spectral-faithful&apos; is the thesis&apos;s line-intersection matcher as written (Radon lines, eigenvector and Voronoi/Hausdorff spectral matching), which rarely finds enough correct matches to register.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="119"/>
        <source>Registers a SAR image onto a SAR reference (another date, band or polarisation) despite speckle: a nonlinear diffusion scale space whose conductance uses the speckle-robust ROEWA gradient, SIFT keypoints and descriptors on it, keypoints kept only where phase congruency shows real structure, ratio-test matching, seeded RANSAC, then correlation refinement on a grid at full resolution. Set what the rasters hold (amplitude, intensity or dB; complex data is read as amplitude). Product defaults pre-smooth and use a one-way ratio test; the CLI method &apos;ndsift-pc-faithful&apos; is the paper as written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="148"/>
        <source>Registers an optical satellite image onto a reference with any rotation between them: CenSurE octagon keypoints described by the rotation-invariant LBP descriptor (rings, intensity-order sub-regions, centre-symmetric LBP in each pixel&apos;s radial frame; no orientation step), mutual ratio-test matching, seeded RANSAC and the chosen transformation fitted on well-spread GCPs. Product defaults add sub-pixel keypoints and smoothed, radius-2 codes; the CLI method &apos;rilbp-faithful&apos; is the paper as written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="166"/>
        <source>Registers an aerial (or any optical) image onto a satellite reference quickly: SIFT difference-of-Gaussian keypoints detected on a thresholded Sobel edge image, rBRIEF binary descriptors steered by the intensity centroid, removal of self-similar keypoints, mutual Hamming matching and RANSAC with affine samples. Few, strong keypoints make it several times faster than SIFT. Product defaults describe each keypoint at its own scale and add a ratio test; the CLI method &apos;sibrif-faithful&apos; is the paper as written.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="178"/>
        <source>Registers a target of another modality than the reference (SAR, infrared, a depth rendering, a web map, night lights onto optical imagery) at any rotation and at scales from 1/2 to 2: phase-congruency (RIFT) features vote for rotation and scale, each hypothesis is checked densely with CFOG structural descriptors, the best are refined by matching RIFT descriptors near their predicted positions, and the result is refined at full resolution with CFOG and checked independently. Its baseline, the published RIFT2 matcher, is the CLI method &apos;rift&apos;.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="18"/>
        <source>outlier threshold, working pixels</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="35"/>
        <source>None: fit every correspondence</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="46"/>
        <source>band of the reference to match</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="56"/>
        <source>Local grid spacing (reference px; 0: auto)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="57"/>
        <source>local correction grid spacing, reference px (0: automatic, about 2000 windows over the overlap)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="59"/>
        <source>pixel-to-pixel registration onto a reference without georeferencing: its pixel grid stands in for the map and the outputs carry no CRS (without this, such a reference is refused)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="90"/>
        <source>warped raster: gtiff (tiled, DEFLATE), cog (cloud-optimised, with overviews) or vrt (a warped VRT reading the target, written as registered.vrt)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="98"/>
        <source>how pixels outside the target are marked: auto (the target&apos;s nodata or collar value, NaN for floats, else an alpha band, so valid zeros stay valid), alpha, or nodata</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/options.py" line="59"/>
        <source>empty</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="60"/>
        <source>Search area</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="61"/>
        <source>where to look for a target without usable georeferencing: xmin,ymin,xmax,ymax with an optional CRS after a comma (default CRS: the reference&apos;s, longitude and latitude for a map service)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="62"/>
        <source>the whole reference; required with a map service</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="323"/>
        <source>on</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="341"/>
        <source>May help: {} ({}).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="82"/>
        <source>Target&apos;s own pixels (not resampled)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="160"/>
        <source>Windows per side of the grid over the overlap.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="163"/>
        <source>Share of a window&apos;s pixels that must be valid in both images.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="164"/>
        <source>Lowest accepted phase-correlation peak of a window.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="245"/>
        <source>Strongest keypoints kept per image (XFeat&apos;s default).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="246"/>
        <source>Cosine similarity a mutual nearest neighbour needs (XFeat&apos;s default).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="247"/>
        <source>Turns of the target tried, either way, in steps of 45 degrees: 0 when the target is upright on the reference (resampled onto it by its georeferencing), 180 for any rotation.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="248"/>
        <source>Both images are matched shrunk alike to at most this many pixels each: XFeat describes at an eighth of the resolution it is given, and the full-resolution refinement restores the precision (four times faster than at the 4 Mpx working size).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="161"/>
        <source>Side of each correlation window, working px (halved for small overlaps).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="162"/>
        <source>Longest side of the coarse whole-overlap correlation, px.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="6"/>
        <source>automatic</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="14"/>
        <source>Automatic (chosen by the check)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/catalogue.py" line="33"/>
        <source>Georeference a scanned map by its grid</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/catalogue.py" line="33"/>
        <source>Georeferences a scanned map sheet by the grid or graticule printed on it, without a reference layer. Choose the sheet&apos;s CRS. The coordinates printed in its margins are read (Tesseract); where they cannot be, place two or three crossings of the printed lines roughly in the QGIS Georeferencer, type their coordinates as printed (degrees, or metres of the national grid) and save the GCP points (.points) as hints. Hamta finds the printed lattice as a whole, then every crossing of the sheet to a fraction of a pixel; each crossing becomes a GCP. The model (affine, a polynomial where the projection bends the lines, a thin plate spline where the paper is warped) is checked by predicting each grid line from the others: a result is verified only when that check is within the accuracy asked for, in scan pixels. A sheet whose grid cannot be found is refused, saying why.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="136"/>
        <source>Reference layer (raster, XYZ, WMS, areas or lines)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="143"/>
        <source>Smallest region kept, working px.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="146"/>
        <source>At most this many target regions, the largest, score a similarity: a bound on the search&apos;s time where a scan holds tens of thousands (letters, specks).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="140"/>
        <source>Register a scanned map onto a layer of areas (regions)</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="141"/>
        <source>Registers a target whose closed shapes (lakes, blocks, fields) the reference shows too, in another look: a scanned map onto a layer of the areas it shows (a vector layer of water or buildings, drawn as a raster), at any rotation and scale. The regions of each image, cut at many grey levels, are matched by where they lie together; their centroids are refined at full resolution with CFOG and the result checked independently.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="142"/>
        <source>Grey levels (percentiles) at which regions are cut from each image.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="144"/>
        <source>Each image is matched at most this size (the larger of the two is brought to the smaller&apos;s pixel count first).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="145"/>
        <source>Largest target regions each paired with every large reference region to propose a similarity.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="244"/>
        <source>Hamta stopped on an unexpected error ({}: {}); no output was written. Please report it (the traceback is in the log, tab Hamta).</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="272"/>
        <source> What was read and tried: {}</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="336"/>
        <source>Verified by an independent check: {}; estimated error within {}.</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="50"/>
        <source>a cap on the seconds &apos;auto&apos; and a basemap search may spend: then the method running is stopped (the first, the fast path, always completes) and no further method or place starts. Without it what they try is bounded by counts (methods, places, requests), so the verdict is the same on any machine and under any load; with it, a slower or busier machine may try less</source>
        <translation type="unfinished"></translation>
    </message>
    <message>
        <location filename="core_strings.py" line="51"/>
        <source>no cap</source>
        <translation type="unfinished"></translation>
    </message>
</context>
</TS>
