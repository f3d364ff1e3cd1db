<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="fa">
<context>
    <name>@default</name>
    <message>
        <location filename="../plugin/action.py" line="50"/>
        <source>Hamta cannot run: {}</source>
        <translation>همتا اجرا نمی‌شود: {}</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="60"/>
        <source>The reference layer &apos;{}&apos; could not be read ({}: {}).</source>
        <translation>لایهٔ مرجع «{}» خوانده نشد ({}: {}).</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="63"/>
        <source>Auto-georeference &apos;{}&apos;</source>
        <translation>زمین‌مرجع‌سازی خودکار «{}»</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="102"/>
        <source>Auto-georeference of &apos;{}&apos; canceled; nothing was added.</source>
        <translation>زمین‌مرجع‌سازی خودکار «{}» لغو شد؛ چیزی افزوده نشد.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="107"/>
        <source>Open the GCPs in the Georeferencer</source>
        <translation>باز کردن نقاط کنترل در زمین‌مرجع‌ساز</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="107"/>
        <source>&apos;{}&apos; was registered, but the independent check did not confirm it ({}). No georeferenced raster was written; see the report, or tick &apos;Keep unverified result&apos; to write it anyway.</source>
        <translation type="obsolete">«{}» ثبت شد، اما بررسی مستقل آن را تأیید نکرد ({}). رستر زمین‌مرجع نوشته نشد؛ گزارش را ببینید، یا «نگه داشتن نتیجهٔ تأییدنشده» را بزنید تا به هر حال نوشته شود.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="122"/>
        <source>Hamta stopped on an unexpected error ({}: {}); nothing was added. Please report it (the details are in the message log).</source>
        <translation>همتا با خطایی پیش‌بینی‌نشده متوقف شد ({}: {})؛ چیزی افزوده نشد. لطفاً آن را گزارش کنید (جزئیات در گزارش پیام‌ها است).</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="147"/>
        <source>{} (georeferenced)</source>
        <translation>{} (زمین‌مرجع)</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="149"/>
        <source>{} GCPs</source>
        <translation>نقاط کنترل {}</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="154"/>
        <source>The output &apos;{}&apos; could not be loaded.</source>
        <translation>خروجی «{}» بارگذاری نشد.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="109"/>
        <source>, error within {:.2f} px</source>
        <translation type="obsolete">، خطا کمتر از {:.2f} پیکسل</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="110"/>
        <source>&apos;{}&apos; is georeferenced, {} GCPs, and verified by an independent check: {} of {} sites agree{}.</source>
        <translation type="obsolete">«{}» زمین‌مرجع شد، {} نقطهٔ کنترل، و بررسی مستقل آن را تأیید کرد: {} از {} محل موافق‌اند{}.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="112"/>
        <source>&apos;{}&apos; is georeferenced but NOT VERIFIED ({}); check it before use.</source>
        <translation type="obsolete">«{}» زمین‌مرجع شد اما تأیید نشد ({})؛ پیش از استفاده آن را بررسی کنید.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="112"/>
        <source>not checked</source>
        <translation type="obsolete">بررسی نشده</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="178"/>
        <source>Open report</source>
        <translation>باز کردن گزارش</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="187"/>
        <source>In the Georeferencer</source>
        <translation>در زمین‌مرجع‌ساز</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="187"/>
        <source>In Raster ▸ Georeferencer</source>
        <translation>در رستر ◂ زمین‌مرجع‌ساز</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="188"/>
        <source>{}, open the raster '{}' (File ▸ Open Raster…), then File ▸ Load GCP Points… and paste the path of the GCP file, now on the clipboard: {}</source>
        <translation>{}، رستر «{}» را باز کنید (پرونده ◂ باز کردن رستر…)، سپس پرونده ◂ بارگذاری نقاط کنترل… و مسیر پروندهٔ نقاط کنترل را که اکنون در حافظهٔ موقت است بچسبانید: {}</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="275"/>
        <source>Auto-georeference</source>
        <translation>زمین‌مرجع‌سازی خودکار</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="127"/>
        <source>The raster file to georeference (a raster layer read by GDAL).</source>
        <translation>پروندهٔ رستری که باید زمین‌مرجع شود (لایهٔ رستری که GDAL می‌خواند).</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="128"/>
        <source>Target raster</source>
        <translation>رستر هدف</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="114"/>
        <source>The georeferenced layer to match the target on: a basemap (XYZ tiles, WMS, WMTS...) or a raster. The results are in its CRS.</source>
        <translation type="obsolete">لایهٔ زمین‌مرجعی که هدف روی آن تطبیق داده می‌شود: یک نقشهٔ پایه (کاشی‌های XYZ، WMS، WMTS...) یا یک رستر. نتایج در سامانهٔ مختصات آن است.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="139"/>
        <source>Reference layer</source>
        <translation>لایهٔ مرجع</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="154"/>
        <source>On by default for a target without georeferencing (the map canvas extent). On for a georeferenced target, Hamta ignores the target&apos;s georeferencing and searches here.</source>
        <translation>برای هدفِ بی‌زمین‌مرجع به‌طور پیش‌فرض روشن است (محدودهٔ بوم نقشه). اگر برای هدفِ زمین‌مرجع روشن شود، همتا زمین‌مرجعِ هدف را نادیده می‌گیرد و این‌جا را می‌جوید.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="164"/>
        <source>Search area, {} (where to look for the target)</source>
        <translation>محدودهٔ جست‌وجو، {} (جایی که هدف جست‌وجو می‌شود)</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="168"/>
        <source>A folder for the warped raster, the GCPs (GeoPackage and .points) and the reports; files of an earlier run there are replaced.</source>
        <translation>پوشه‌ای برای رستر تبدیل‌شده، نقاط کنترل (GeoPackage و ‎.points) و گزارش‌ها؛ پرونده‌های اجرای قبلی در آن جایگزین می‌شوند.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="147"/>
        <source>Keep unverified result</source>
        <translation type="obsolete">نگه داشتن نتیجهٔ تأییدنشده</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="171"/>
        <source>Write the georeferenced raster even when the independent check does not confirm the result (it is then marked NOT VERIFIED).</source>
        <translation>رستر زمین‌مرجع را حتی وقتی بررسی مستقل نتیجه را تأیید نمی‌کند بنویس (با برچسب «تأیید نشده»).</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="173"/>
        <source>Output folder</source>
        <translation>پوشهٔ خروجی</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="177"/>
        <source>Run</source>
        <translation>اجرا</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="250"/>
        <source>Choose the raster to georeference (add it to the project first).</source>
        <translation>رستری را که باید زمین‌مرجع شود انتخاب کنید (نخست آن را به پروژه بیفزایید).</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="258"/>
        <source>Choose a reference layer other than the target: a basemap or a georeferenced raster.</source>
        <translation>لایهٔ مرجعی جز هدف انتخاب کنید: یک نقشهٔ پایه یا رستری زمین‌مرجع.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="264"/>
        <source>Choose an output folder.</source>
        <translation>یک پوشهٔ خروجی انتخاب کنید.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="267"/>
        <source>&apos;{}&apos; has no georeferencing: turn on the search area (the map canvas extent by default) so that Hamta knows where to look in &apos;{}&apos;.</source>
        <translation>«{}» زمین‌مرجع ندارد: محدودهٔ جست‌وجو را روشن کنید (به‌طور پیش‌فرض محدودهٔ بوم نقشه) تا همتا بداند در «{}» کجا را بجوید.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="71"/>
        <source>Auto-georeference &apos;{}&apos;: starting</source>
        <translation type="obsolete">زمین‌مرجع‌سازی خودکار '{}': آغاز</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="80"/>
        <source>Cancel</source>
        <translation>لغو</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="75"/>
        <source>Auto-georeference &apos;{}&apos;: {}</source>
        <translation>زمین‌مرجع‌سازی خودکار '{}': {}</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="117"/>
        <source>Details</source>
        <translation>جزئیات</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="141"/>
        <source> (error within {:.1f} px)</source>
        <translation type="obsolete"> (خطا حداکثر {:.1f} پیکسل)</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="165"/>
        <source>&apos;{}&apos; is georeferenced and verified{}.</source>
        <translation type="obsolete">'{}' زمین‌مرجع شد و درستی آن تأیید شد{}.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="168"/>
        <source>&apos;{}&apos; is georeferenced but NOT VERIFIED; check it before use.</source>
        <translation type="obsolete">'{}' زمین‌مرجع شد اما تأیید نشد؛ پیش از استفاده آن را بررسی کنید.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="257"/>
        <source>&apos;{}&apos; onto &apos;{}&apos;</source>
        <translation>'{}' روی '{}'</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="190"/>
        <source>Independent check: {}; {} of {} sites agree; error bound {} px (tolerance {:g} px)</source>
        <translation type="obsolete">بررسی مستقل: {}؛ {} از {} محل موافق‌اند؛ کران خطا {} پیکسل (رواداری {:g} پیکسل)</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="269"/>
        <source>Method: {}; {} GCPs; transformation: {}</source>
        <translation>روش: {}؛ {} نقطهٔ کنترل زمینی؛ تبدیل: {}</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="273"/>
        <source>Time: {:.1f} s</source>
        <translation>زمان: {:.1f} ثانیه</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="76"/>
        <source>starting</source>
        <translation>آغاز</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="113"/>
        <source>Keep anyway</source>
        <translation>به هر حال نگه دار</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="113"/>
        <source>Not verified: &apos;{}&apos; was not placed with confidence, so nothing was added.</source>
        <translation type="obsolete">تأیید نشد: جای «{}» با اطمینان یافته نشد، پس چیزی افزوده نشد.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="135"/>
        <source>Keep &apos;{}&apos; (not verified)</source>
        <translation>نگه داشتن «{}» (تأییدنشده)</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="139"/>
        <source>Keeping &apos;{}&apos;: {}</source>
        <translation>نگه داشتن «{}»: {}</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="142"/>
        <source>{} (georeferenced, NOT VERIFIED)</source>
        <translation type="obsolete">{} (زمین‌مرجع، تأییدنشده)</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="165"/>
        <source> (error within {})</source>
        <translation type="obsolete"> (خطا حداکثر {})</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="225"/>
        <source>{:.1f} m on the ground</source>
        <translation>{:.1f} متر روی زمین</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="225"/>
        <source>{:.2f} m on the ground</source>
        <translation>{:.2f} متر روی زمین</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="228"/>
        <source>{:.1f} px of &apos;{}&apos;</source>
        <translation>{:.1f} پیکسلِ «{}»</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="255"/>
        <source>Independent check: {}; {} of {} sites agree; error within {} (tolerance {})</source>
        <translation type="obsolete">بررسی مستقل: {}؛ {} از {} محل موافق‌اند؛ خطا حداکثر {} (رواداری {})</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="267"/>
        <source>What may help:</source>
        <translation>آنچه ممکن است کمک کند:</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="275"/>
        <source>Kept after the run: the outputs were written in {:.1f} s.</source>
        <translation>پس از اجرا نگه داشته شد: خروجی‌ها در {:.1f} ثانیه نوشته شدند.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="286"/>
        <source>&apos;Keep anyway&apos; here, or &apos;{}&apos; in the dialog: {}</source>
        <translation>«به هر حال نگه دار» در همین‌جا، یا «{}» در پنجره: {}</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="289"/>
        <source>Search area</source>
        <translation>محدودهٔ جست‌وجو</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="170"/>
        <source>Keep unverified results</source>
        <translation>نگه‌داشتن نتایج تأییدنشده</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="114"/>
        <source>&apos;{}&apos; not verified; nothing added.</source>
        <translation>'{}' تأیید نشد؛ چیزی افزوده نشد.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="147"/>
        <source>NOT VERIFIED {} (georeferenced)</source>
        <translation>تأییدنشده {} (زمین‌مرجع)</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="170"/>
        <source>&apos;{}&apos; verified{}.</source>
        <translation>'{}' تأیید شد{}.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="170"/>
        <source>, within {}</source>
        <translation>، با خطای کمتر از {}</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="171"/>
        <source>&apos;{}&apos; NOT VERIFIED; check it before use.</source>
        <translation>'{}' تأیید نشد؛ پیش از استفاده آن را بررسی کنید.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="258"/>
        <source>&apos;{}&apos; by its own printed grid</source>
        <translation>«{}» با شبکهٔ چاپ‌شده روی خودش</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="123"/>
        <source>The georeferenced layer to match the target on: a basemap (XYZ tiles, WMS, WMTS...) or a raster. The results are in its CRS. None: a scanned map is georeferenced by the grid printed on it.</source>
        <translation type="obsolete">لایهٔ زمین‌مرجع که هدف روی آن تطبیق داده می‌شود: یک نقشهٔ پایه (کاشی‌های XYZ، WMS، WMTS...) یا یک رستر. نتایج در CRS آن است. هیچ‌کدام: نقشهٔ اسکن‌شده با شبکهٔ چاپ‌شده روی آن زمین‌مرجع می‌شود.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="197"/>
        <source>By the sheet&apos;s own grid (no reference layer)</source>
        <translation>با شبکهٔ خود برگه (بدون لایهٔ مرجع)</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="203"/>
        <source>The sheet&apos;s projection: the results are in it (sheets rarely print it).</source>
        <translation>تصویر نقشهٔ برگه: نتایج در آن است (برگه‌ها به‌ندرت آن را چاپ می‌کنند).</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="204"/>
        <source>CRS of the sheet</source>
        <translation>CRS برگه</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="206"/>
        <source>GCP points (*.points)</source>
        <translation>نقاط کنترل (*.points)</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="191"/>
        <source>Two or three crossings of the printed lines placed roughly in the Georeferencer with their coordinates as printed, saved as GCP points.</source>
        <translation type="obsolete">دو یا سه تقاطع خطوط چاپ‌شده که تقریبی در زمین‌مرجع‌ساز گذاشته شده‌اند، با مختصاتی که چاپ شده، ذخیره‌شده به‌صورت نقاط کنترل.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="211"/>
        <source>Hints (.points)</source>
        <translation>راهنماها (.points)</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="253"/>
        <source>Choose the CRS of the sheet, or a reference layer.</source>
        <translation>CRS برگه یا یک لایهٔ مرجع را انتخاب کنید.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="236"/>
        <source>Choose the hints: two or three crossings placed in the Georeferencer with their coordinates, saved as GCP points (.points); or choose a reference layer.</source>
        <translation type="obsolete">راهنماها را انتخاب کنید: دو یا سه تقاطع که در زمین‌مرجع‌ساز با مختصاتشان گذاشته و به‌صورت نقاط کنترل (.points) ذخیره شده‌اند؛ یا یک لایهٔ مرجع انتخاب کنید.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="208"/>
        <source>Two or three crossings of the printed lines placed roughly in the Georeferencer with their coordinates as printed, saved as GCP points; empty: the labels printed in the sheet&apos;s margins are read.</source>
        <translation>دو یا سه تقاطع خطوط چاپ‌شده که تقریبی در زمین‌مرجع‌ساز با مختصاتی که چاپ شده گذاشته و به‌صورت نقاط کنترل ذخیره شده‌اند؛ خالی: برچسب‌های چاپ‌شده در حاشیهٔ برگه خوانده می‌شوند.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="255"/>
        <source>The hints file does not exist: choose the GCP points (.points) saved in the Georeferencer, or leave it empty to have the sheet&apos;s printed labels read.</source>
        <translation>پروندهٔ راهنماها وجود ندارد: نقاط کنترل (.points) ذخیره‌شده در زمین‌مرجع‌ساز را انتخاب کنید، یا خالی بگذارید تا برچسب‌های چاپ‌شدهٔ برگه خوانده شوند.</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="201"/>
        <source>choose the sheet&apos;s projection</source>
        <translation>تصویر نقشهٔ برگه را انتخاب کنید</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="207"/>
        <source>empty: the coordinates printed in the margins are read</source>
        <translation>خالی: مختصات چاپ‌شده در حاشیه خوانده می‌شود</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="135"/>
        <source>The georeferenced layer to match the target on: a basemap (XYZ tiles, WMS, WMTS...), a raster, or a layer of areas or lines (water, buildings, roads: for a scanned map). The results are in its CRS. None: a scanned map is georeferenced by the grid printed on it.</source>
        <translation>لایهٔ زمین‌مرجعی که هدف روی آن تطبیق داده می‌شود: یک نقشهٔ پایه (کاشی‌های XYZ، WMS، WMTS...)، یک رستر، یا لایه‌ای از سطوح یا خطوط (آب، ساختمان‌ها، راه‌ها: برای نقشهٔ اسکن‌شده). نتایج در CRS آن است. هیچ: نقشهٔ اسکن‌شده با شبکهٔ چاپ‌شده روی آن زمین‌مرجع می‌شود.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="118"/>
        <source>&apos;{}&apos; not georeferenced; nothing added.</source>
        <translation>«{}» زمین‌مرجع نشد؛ چیزی افزوده نشد.</translation>
    </message>
    <message>
        <location filename="../plugin/action.py" line="260"/>
        <source>Independent check: {}; {}; error within {} (tolerance {})</source>
        <translation>بررسی مستقل: {}؛ {}؛ خطا حداکثر {} (رواداری {})</translation>
    </message>
    <message>
        <location filename="../plugin/autogeoref.py" line="260"/>
        <source>&apos;{}&apos; has no georeferencing, so it cannot be the reference: choose a basemap or a georeferenced raster, or no reference layer to georeference &apos;{}&apos; by its printed grid.</source>
        <translation>«{}» زمین‌مرجع ندارد، پس نمی‌تواند مرجع باشد: یک نقشهٔ پایه یا رستری زمین‌مرجع‌دار انتخاب کنید، یا برای زمین‌مرجع کردن «{}» با شبکهٔ چاپی‌اش هیچ لایهٔ مرجعی انتخاب نکنید.</translation>
    </message>
</context>
<context>
    <name>AutoGeoreference</name>
    <message>
        <location filename="../plugin/plugin.py" line="61"/>
        <source>Auto-georeference…</source>
        <translation>زمین‌مرجع‌سازی خودکار…</translation>
    </message>
    <message>
        <location filename="../plugin/plugin.py" line="64"/>
        <source>Georeference the selected raster layer on the visible basemap (Hamta)</source>
        <translation>زمین‌مرجع‌سازی لایهٔ رستری برگزیده روی نقشهٔ پایهٔ نمایان (همتا)</translation>
    </message>
</context>
<context>
    <name>BatchRegisterAlgorithm</name>
    <message>
        <location filename="../processing/catalogue.py" line="32"/>
        <source>Batch register</source>
        <translation>ثبت دسته‌ای</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="63"/>
        <source>Registration</source>
        <translation>ثبت هندسی</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="87"/>
        <source>Target rasters</source>
        <translation>رسترهای هدف</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="89"/>
        <source>Reference raster (for the targets above)</source>
        <translation>رستر مرجع (برای هدف‌های بالا)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="89"/>
        <source>Job list instead (CSV or GeoPackage: target, reference, method, model, output)</source>
        <translation type="obsolete">یا فهرست کار (CSV یا GeoPackage: target، reference، method، model، output)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="91"/>
        <source>Job lists (*.csv *.gpkg)</source>
        <translation>فهرست‌های کار (*.csv *.gpkg)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="102"/>
        <source>Method</source>
        <translation>روش</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="104"/>
        <source>Keep unverified results</source>
        <translation>نگه‌داشتن نتایج تأییدنشده</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="112"/>
        <source>Workers of the local cluster (0: one per CPU)</source>
        <translation>کارگرهای خوشهٔ محلی (۰: یکی برای هر پردازنده)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="115"/>
        <source>Output folder</source>
        <translation>پوشهٔ خروجی</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="116"/>
        <source>Batch results (footprints)</source>
        <translation>نتایج دسته (ردپاها)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="117"/>
        <source>Choose target rasters and a reference raster, or a job list.</source>
        <translation type="obsolete">رسترهای هدف و یک رستر مرجع، یا یک فهرست کار را انتخاب کنید.</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="163"/>
        <source>Batch stopped on an unexpected error ({}: {}).</source>
        <translation>اجرای دسته با یک خطای پیش‌بینی‌نشده متوقف شد ({}: {}).</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="71"/>
        <source>Registers many targets in one run: the rasters chosen as targets onto one reference, or every row of a job list (CSV or GeoPackage with columns target, reference, method, model, output). Pairs run in parallel on Dask: a local cluster of threads inside QGIS (reachable only with TLS credentials made for the run), or an existing scheduler given as tls://host:port, with the certificates of Dask&apos;s configuration (distributed.comm.tls.*; tcp:// works but is unauthenticated). Each pair writes its outputs into its own folder under the output folder (a job list&apos;s output: a folder inside it); a pair that fails is recorded and the others go on; running again skips the pairs already done. The result layer holds every target&apos;s footprint with its verdict, error figures, method, time and output paths.

QGIS&apos;s own batch mode over the single-pair algorithms works too.</source>
        <translation type="obsolete">چندین تصویر هدف را در یک اجرا ثبت می‌کند: رسترهای انتخاب‌شده به‌عنوان هدف روی یک مرجع، یا هر سطر از یک فهرست کار (CSV یا GeoPackage با ستون‌های target، reference، method، model و output). جفت‌ها به‌طور موازی روی Dask اجرا می‌شوند: یک خوشهٔ محلی از رشته‌ها درون QGIS (که فقط با اعتبارنامه‌های TLS ساخته‌شده برای همین اجرا در دسترس است)، یا زمان‌بندی موجودی که با tls://host:port داده می‌شود، با گواهی‌های پیکربندی Dask (distributed.comm.tls.*؛ tcp:// هم کار می‌کند اما بدون احراز هویت است). هر جفت خروجی‌هایش را در پوشهٔ خودش زیر پوشهٔ خروجی می‌نویسد (خروجی یک فهرست کار: پوشه‌ای درون آن)؛ جفتی که شکست بخورد ثبت می‌شود و بقیه ادامه می‌یابند؛ اجرای دوباره جفت‌های انجام‌شده را رد می‌کند. لایهٔ نتیجه ردپای هر تصویر هدف را با حکم بررسی، ارقام خطا، روش، زمان و مسیر خروجی‌ها نگه می‌دارد.

حالت دسته‌ای خود QGIS روی الگوریتم‌های تک‌جفتی نیز کار می‌کند.</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="110"/>
        <source>Dask scheduler (tls://host:port; empty: a local cluster)</source>
        <translation>زمان‌بند Dask (tls://host:port؛ خالی: یک خوشهٔ محلی)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="91"/>
        <source>Job list instead (CSV or GeoPackage)</source>
        <translation>یا فهرست کار (CSV یا GeoPackage)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="108"/>
        <source>Dask scheduler (tls://host:port)</source>
        <translation>زمان‌بند Dask (tls://host:port)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="137"/>
        <source>The reference layer &apos;{}&apos; ({}) cannot be read by every pair of a batch: use a raster file, an XYZ or WMS layer, or save the layer&apos;s area as a GeoTIFF first.</source>
        <translation>لایهٔ مرجع «{}» ({}) را همهٔ جفت‌های یک دسته نمی‌توانند بخوانند: یک پروندهٔ رستری یا لایهٔ XYZ یا WMS به کار ببرید، یا نخست محدودهٔ لایه را به‌صورت GeoTIFF ذخیره کنید.</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="72"/>
        <source>Registers many targets in one run: the rasters chosen as targets onto one reference, or every row of a job list (CSV or GeoPackage with columns target, reference, method, model, output). Pairs run in parallel on Dask: a local cluster of threads inside QGIS (reachable only with TLS credentials made for the run), or an existing scheduler given as tls://host:port, with the certificates of Dask&apos;s configuration (distributed.comm.tls.*; tcp:// works but is unauthenticated). Each pair writes its outputs into its own folder under the output folder (a job list&apos;s output: a folder inside it); a pair that fails is recorded and the others go on; running again skips the pairs already done. The result layer holds every target&apos;s footprint with its verdict, error figures, method, time and output paths.

Scanned sheets of a map series: choose no reference but the CRS of their printed coordinates; each sheet is georeferenced by its own printed grid (its labels read, or the hints of the Georeferencer&apos;s &apos;&lt;raster&gt;.points&apos; beside it); a job list does the same with its &apos;crs&apos; and &apos;hints&apos; columns.

QGIS&apos;s own batch mode over the single-pair algorithms works too.</source>
        <translation>چندین تصویر هدف را در یک اجرا ثبت می‌کند: رسترهای انتخاب‌شده به‌عنوان هدف روی یک مرجع، یا هر سطر از یک فهرست کار (CSV یا GeoPackage با ستون‌های target، reference، method، model و output). جفت‌ها به‌طور موازی روی Dask اجرا می‌شوند: یک خوشهٔ محلی از رشته‌ها درون QGIS (که فقط با اعتبارنامه‌های TLS ساخته‌شده برای همین اجرا در دسترس است)، یا زمان‌بندی موجودی که با tls://host:port داده می‌شود، با گواهی‌های پیکربندی Dask (distributed.comm.tls.*؛ tcp:// هم کار می‌کند اما بدون احراز هویت است). هر جفت خروجی‌هایش را در پوشهٔ خودش زیر پوشهٔ خروجی می‌نویسد (خروجی یک فهرست کار: پوشه‌ای درون آن)؛ جفتی که شکست بخورد ثبت می‌شود و بقیه ادامه می‌یابند؛ اجرای دوباره جفت‌های انجام‌شده را رد می‌کند. لایهٔ نتیجه ردپای هر تصویر هدف را با حکم بررسی، ارقام خطا، روش، زمان و مسیر خروجی‌ها نگه می‌دارد.

برگه‌های اسکن‌شدهٔ یک سری نقشه: هیچ مرجعی انتخاب نکنید، بلکه CRS مختصات چاپی آن‌ها را؛ هر برگه با شبکهٔ چاپی خودش زمین‌مرجع می‌شود (برچسب‌هایش خوانده می‌شوند، یا راهنماهای فایل «&lt;raster&gt;.points» زمین‌مرجع‌ساز کنارش)؛ فهرست کار همین را با ستون‌های «crs» و «hints» انجام می‌دهد.

حالت دسته‌ای خود QGIS روی الگوریتم‌های تک‌جفتی هم کار می‌کند.</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="93"/>
        <source>Job list instead (CSV or GeoPackage: target, reference, method, model, crs, hints, output)</source>
        <translation>یا فهرست کار (CSV یا GeoPackage: target، reference، method، model، crs، hints، output)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="96"/>
        <source>CRS of printed coordinates (sheets)</source>
        <translation>CRS مختصات چاپی (برگه‌ها)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="98"/>
        <source>Scanned sheets georeferenced by their own printed grid: what their printed coordinates count in (EPSG:4326 or EPSG:4269 for degrees, the national grid&apos;s CRS for its metres, feet or yards)</source>
        <translation>برگه‌های اسکن‌شده‌ای که با شبکهٔ چاپی خود زمین‌مرجع می‌شوند: مختصات چاپی آن‌ها به چه واحدی است (EPSG:4326 یا EPSG:4269 برای درجه، CRS شبکهٔ ملی برای متر، فوت یا یارد آن)</translation>
    </message>
    <message>
        <location filename="../processing/batch_algorithm.py" line="132"/>
        <source>Choose target rasters and a reference raster (or, for scanned sheets by their printed grid, the CRS of their printed coordinates), or a job list.</source>
        <translation>رسترهای هدف و یک رستر مرجع (یا، برای برگه‌های اسکن‌شده با شبکهٔ چاپی‌شان، CRS مختصات چاپی آن‌ها)، یا یک فهرست کار را انتخاب کنید.</translation>
    </message>
</context>
<context>
    <name>GridAlgorithm</name>
    <message>
        <location filename="../processing/grid_algorithm.py" line="50"/>
        <source>georeference,scanned map,grid,graticule,sheet,GCP,crossings</source>
        <translation>زمین‌مرجع,نقشهٔ اسکن‌شده,شبکه,شبکهٔ جغرافیایی,برگه,نقطهٔ کنترل,تقاطع</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="53"/>
        <source>Scanned map (to georeference)</source>
        <translation>نقشهٔ اسکن‌شده (برای زمین‌مرجع کردن)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="56"/>
        <source>CRS of the sheet (its projection)</source>
        <translation type="obsolete">CRS برگه (تصویر نقشهٔ آن)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="57"/>
        <source>Hints: crossings with their coordinates (.points)</source>
        <translation type="obsolete">راهنماها: تقاطع‌ها با مختصاتشان (.points)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="59"/>
        <source>Two or three crossings of the printed lines placed roughly in the QGIS Georeferencer, with their coordinates as printed (degrees, or metres of the grid), saved as GCP points</source>
        <translation type="obsolete">دو یا سه تقاطع خطوط چاپ‌شده که تقریبی در زمین‌مرجع‌ساز QGIS گذاشته شده‌اند، با مختصاتی که چاپ شده (درجه، یا متر شبکه)، ذخیره‌شده به‌صورت نقاط کنترل</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="65"/>
        <source>Keep unverified results</source>
        <translation>نگه‌داشتن نتایج تأییدنشده</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="73"/>
        <source>Grid step (printed units)</source>
        <translation>گام شبکه (به واحد چاپ‌شده)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="73"/>
        <source>The step of the printed grid, in its coordinates (empty: the largest usual step the hints fit whose lines are printed)</source>
        <translation type="obsolete">گام شبکهٔ چاپ‌شده، به مختصات آن (خالی: بزرگ‌ترین گام متداولی که راهنماها با آن جورند و خطوطش چاپ شده است)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="54"/>
        <source>CRS of the printed coordinates</source>
        <translation>CRS مختصات چاپ‌شده</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="77"/>
        <source>What the printed coordinates count in (empty: degrees of the sheet&apos;s datum when they look like degrees, else the sheet&apos;s CRS)</source>
        <translation type="obsolete">مختصات چاپ‌شده به چه واحدی است (خالی: درجهٔ داده‌مبنای برگه وقتی شبیه درجه‌اند، وگرنه CRS برگه)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="85"/>
        <source>Choose the CRS of the sheet.</source>
        <translation type="obsolete">CRS برگه را انتخاب کنید.</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="59"/>
        <source>Two or three crossings of the printed lines placed roughly in the QGIS Georeferencer, with their coordinates as printed (degrees, or metres of the grid), saved as GCP points (empty: the labels printed in the sheet&apos;s margins are read, with Tesseract)</source>
        <translation type="obsolete">دو یا سه تقاطع خطوط چاپ‌شده که تقریبی در زمین‌مرجع‌ساز QGIS گذاشته شده‌اند، با مختصاتی که چاپ شده (درجه، یا متر شبکه)، ذخیره‌شده به‌صورت نقاط کنترل (خالی: برچسب‌های چاپ‌شده در حاشیهٔ برگه با Tesseract خوانده می‌شوند)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="59"/>
        <source>Hints: crossings placed (.points)</source>
        <translation>راهنماها: تقاطع‌های گذاشته‌شده (.points)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="55"/>
        <source>What the coordinates printed on the sheet count in: EPSG:4326 or EPSG:4269 for degrees of a graticule (whatever projection it is drawn in: it is found), the national grid&apos;s CRS for its metres, feet or yards</source>
        <translation>مختصات چاپ‌شده روی برگه به چه واحدی است: EPSG:4326 یا EPSG:4269 برای درجه‌های یک شبکهٔ جغرافیایی (در هر تصویری که کشیده شده باشد: پیدا می‌شود)، CRS شبکهٔ ملی برای متر، فوت یا یارد آن</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="61"/>
        <source>Two or three crossings of the printed lines placed roughly in the QGIS Georeferencer, with their coordinates as printed (degrees, or the grid&apos;s units), saved as GCP points (empty: the labels printed in the sheet&apos;s margins are read by OCR)</source>
        <translation>دو یا سه تقاطع خطوط چاپی که تقریبی در زمین‌مرجع‌ساز QGIS گذاشته شده‌اند، با مختصات چاپی‌شان (درجه، یا واحد شبکه)، ذخیره‌شده به‌صورت نقاط GCP (خالی: برچسب‌های چاپ‌شده در حاشیه‌های برگه با OCR خوانده می‌شوند)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="75"/>
        <source>The step of the printed grid, in its coordinates (empty: the largest usual step the hints or labels fit whose lines are printed)</source>
        <translation>گام شبکهٔ چاپی، به مختصات خودش (خالی: بزرگ‌ترین گام معمولی که با راهنماها یا برچسب‌ها جور است و خطوطش چاپ شده‌اند)</translation>
    </message>
    <message>
        <location filename="../processing/grid_algorithm.py" line="83"/>
        <source>Choose the CRS of the printed coordinates.</source>
        <translation>CRS مختصات چاپی را انتخاب کنید.</translation>
    </message>
</context>
<context>
    <name>HamtaPlugin</name>
    <message>
        <location filename="../plugin/plugin.py" line="54"/>
        <source>its algorithms cannot run; press &apos;More&apos; for why and how to fix it.</source>
        <translation>الگوریتم‌های آن اجرا نمی‌شوند؛ برای دلیل و راه رفع آن «بیشتر» را بزنید.</translation>
    </message>
</context>
<context>
    <name>HamtaProvider</name>
    <message>
        <location filename="../processing/provider.py" line="148"/>
        <source>Hamta</source>
        <translation>همتا</translation>
    </message>
    <message>
        <location filename="../processing/provider.py" line="151"/>
        <source>Hamta automatic georeferencing</source>
        <translation>زمین‌مرجع‌سازی خودکار همتا</translation>
    </message>
    <message>
        <location filename="../processing/provider.py" line="114"/>
        <source>{} (unavailable: {})</source>
        <translation>{} (در دسترس نیست: {})</translation>
    </message>
    <message>
        <location filename="../processing/provider.py" line="163"/>
        <source>Hamta cannot run ({}): see the algorithm&apos;s help for how to fix it.</source>
        <translation>همتا اجرا نمی‌شود ({}): راه رفع آن را در راهنمای الگوریتم ببینید.</translation>
    </message>
</context>
<context>
    <name>RegisterAlgorithm</name>
    <message>
        <location filename="core_strings.py" line="7"/>
        <source>Similarity (Helmert)</source>
        <translation>تشابهی (هلمرت)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="8"/>
        <source>Affine (polynomial 1)</source>
        <translation>آفین (چندجمله‌ای درجه ۱)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="9"/>
        <source>Projective</source>
        <translation>تصویری</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="10"/>
        <source>Polynomial 2</source>
        <translation>چندجمله‌ای درجه ۲</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="11"/>
        <source>Polynomial 3</source>
        <translation>چندجمله‌ای درجه ۳</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="12"/>
        <source>Thin plate spline</source>
        <translation>اسپلاین صفحه نازک</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="65"/>
        <source>Nearest neighbour</source>
        <translation>نزدیک‌ترین همسایه</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="66"/>
        <source>Bilinear</source>
        <translation>دوخطی</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="67"/>
        <source>Cubic</source>
        <translation>مکعبی</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="68"/>
        <source>Cubic B-spline</source>
        <translation>بی‌اسپلاین مکعبی</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="69"/>
        <source>Lanczos</source>
        <translation>لانچوس</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="79"/>
        <source>Automatic</source>
        <translation>خودکار</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="80"/>
        <source>Reference pixel grid</source>
        <translation>شبکه پیکسلی تصویر مرجع</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="81"/>
        <source>Target&apos;s native resolution</source>
        <translation>تفکیک‌پذیری اصلی تصویر هدف</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="24"/>
        <source>Automatic (when images were decimated)</source>
        <translation>خودکار (وقتی تصاویر کوچک‌نمایی شده باشند)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="25"/>
        <source>Always</source>
        <translation>همیشه</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="26"/>
        <source>Never</source>
        <translation>هرگز</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="39"/>
        <source>Use when it overlaps the reference</source>
        <translation>اگر با مرجع همپوشانی دارد، استفاده شود</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="40"/>
        <source>Always use (fail otherwise)</source>
        <translation>همیشه استفاده شود (در غیر این صورت خطا)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="41"/>
        <source>Ignore</source>
        <translation>نادیده گرفته شود</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="113"/>
        <source>Registration</source>
        <translation>ثبت تصویر</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="128"/>
        <source>georeference,coregistration,registration,GCP,match,align,warp</source>
        <translation>زمین‌مرجع‌سازی,هم‌ثبت‌سازی,ثبت,نقطه کنترل,تطابق,هم‌ترازی,تبدیل</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="135"/>
        <source>Target raster (to georeference)</source>
        <translation>رستر هدف (برای زمین‌مرجع‌سازی)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="4"/>
        <source>Transformation</source>
        <translation>تبدیل</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="63"/>
        <source>Resampling</source>
        <translation>بازنمونه‌برداری</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="45"/>
        <source>Reference band to match</source>
        <translation>باند مرجع برای تطابق</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="37"/>
        <source>Target&apos;s own georeferencing</source>
        <translation>زمین‌مرجع موجود تصویر هدف</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="77"/>
        <source>Output pixel grid</source>
        <translation>شبکه پیکسلی خروجی</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="22"/>
        <source>Full-resolution refinement</source>
        <translation>پالایش در تفکیک‌پذیری کامل</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="15"/>
        <source>Working image size (pixels)</source>
        <translation>اندازه تصویر کاری (پیکسل)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="27"/>
        <source>Maximum number of GCPs</source>
        <translation>بیشینه تعداد نقاط کنترل</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="20"/>
        <source>Random seed</source>
        <translation>بذر تصادفی</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="150"/>
        <source>Georeferenced raster</source>
        <translation>رستر زمین‌مرجع‌شده</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="151"/>
        <source>GCP points</source>
        <translation>نقاط کنترل زمینی</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="153"/>
        <source>GCP file for the QGIS Georeferencer</source>
        <translation>پرونده نقاط کنترل برای Georeferencer کیوجی‌آی‌اس</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="153"/>
        <source>GCP points (*.points)</source>
        <translation>نقاط کنترل (*.points)</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="156"/>
        <source>Target with GCPs, not resampled (VRT)</source>
        <translation>تصویر هدف همراه نقاط کنترل، بدون بازنمونه‌برداری (VRT)</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="156"/>
        <source>VRT (*.vrt)</source>
        <translation>VRT (*.vrt)</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="159"/>
        <source>Report</source>
        <translation>گزارش</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="159"/>
        <source>JSON (*.json)</source>
        <translation>JSON (*.json)</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="166"/>
        <source>RMSE of the GCPs (reference pixels)</source>
        <translation>RMSE نقاط کنترل (پیکسل مرجع)</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="167"/>
        <source>Leave-one-out RMS (reference pixels)</source>
        <translation>RMS به روش حذف تک‌نقطه (پیکسل مرجع)</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="168"/>
        <source>Number of GCPs</source>
        <translation>تعداد نقاط کنترل</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="198"/>
        <source>{} must be a raster file GDAL can read, not a &apos;{}&apos; layer.</source>
        <translation>{} باید پرونده رستری قابل خواندن با GDAL باشد، نه لایه‌ای از نوع «{}».</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="269"/>
        <source>Registration canceled; no outputs were written.</source>
        <translation>ثبت تصویر لغو شد؛ هیچ خروجی‌ای نوشته نشد.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="229"/>
        <source>Register raster (SIFT baseline)</source>
        <translation>ثبت رستر (پایه SIFT)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="147"/>
        <source>Register satellite image (RILBP, rotation-invariant)</source>
        <translation>ثبت تصویر ماهواره‌ای (RILBP، مستقل از دوران)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="165"/>
        <source>Register aerial image onto satellite image (SIBRIF, fast)</source>
        <translation>ثبت تصویر هوایی روی تصویر ماهواره‌ای (SIBRIF، سریع)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="118"/>
        <source>Register SAR image onto SAR image (ND-SIFT + phase congruency)</source>
        <translation>ثبت تصویر SAR روی تصویر SAR (ND-SIFT + همدوسی فاز)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="104"/>
        <source>Register SAR image onto optical image</source>
        <translation>ثبت تصویر SAR روی تصویر نوری</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="164"/>
        <source>Verdict of the independent check</source>
        <translation>رأی بررسی مستقل</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="165"/>
        <source>Method that produced the result</source>
        <translation>روشی که نتیجه را به دست داد</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="276"/>
        <source>The registration was not verified: {}. No georeferenced output was written; set &apos;Keep unverified results&apos; to write it anyway.</source>
        <translation>ثبت تصویر تأیید نشد: {}. هیچ خروجی زمین‌مرجع‌شده‌ای نوشته نشد؛ برای نوشتن آن در هر صورت، گزینهٔ «نگه‌داشتن نتایج تأییدنشده» را فعال کنید.</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="318"/>
        <source>Verified by an independent check: {} of {} sites agree; estimated error within {}.</source>
        <translation type="obsolete">تأییدشده با بررسی مستقل: {} محل از {} محل هم‌خوان‌اند؛ خطای برآوردشده حداکثر {}.</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="339"/>
        <source>NOT VERIFIED ({}): {}</source>
        <translation>تأیید نشد ({}): {}</translation>
    </message>
    <message>
        <location filename="../processing/catalogue.py" line="21"/>
        <source>Register raster (automatic)</source>
        <translation>ثبت رستر (خودکار)</translation>
    </message>
    <message>
        <location filename="../processing/catalogue.py" line="21"/>
        <source>Registers the target raster onto the reference raster and chooses the method itself: the fast SIFT matcher first, then matchers for images of different modality (SAR, infrared, maps) and for SAR, until a result passes an independent check. The check compares the two rasters at sites spread over the overlap, not the matches the model was fitted on, against what wrong alignments of the same rasters give, and bounds the remaining error. A result that does not verify is not written unless &apos;Keep unverified results&apos; is set; the log lists every method tried, its verdict and its time. The other algorithms of this group run one method each, for experts.</source>
        <translation>رستر هدف را روی رستر مرجع ثبت می‌کند و روش را خودش برمی‌گزیند: ابتدا تناظریاب سریع SIFT، سپس تناظریاب‌های ویژهٔ تصاویر با مدالیتهٔ متفاوت (SAR، فروسرخ، نقشه) و ویژهٔ SAR، تا جایی که نتیجه‌ای از یک بررسی مستقل سربلند بیرون آید. این بررسی دو رستر را در محل‌هایی پراکنده در سراسر ناحیهٔ همپوشانی مقایسه می‌کند، نه روی تطابق‌هایی که مدل با آن‌ها برازش شده است، حاصل را با آنچه هم‌ترازی‌های نادرستِ همین رسترها به دست می‌دهند می‌سنجد و برای خطای باقی‌مانده کران تعیین می‌کند. نتیجه‌ای که تأیید نشود نوشته نمی‌شود، مگر اینکه گزینهٔ «نگه‌داشتن نتایج تأییدنشده» فعال باشد؛ گزارش اجرا همهٔ روش‌های آزموده‌شده را همراه با رأی و زمان هر کدام فهرست می‌کند. هر یک از دیگر الگوریتم‌های این گروه فقط یک روش را اجرا می‌کند و برای کاربران متخصص است.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="177"/>
        <source>Register across modalities at any rotation and scale</source>
        <translation>ثبت میان مدالیته‌های مختلف با هر دوران و مقیاس</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="195"/>
        <source>What the SAR (target) raster holds: amplitude, intensity or db.</source>
        <translation>نوع مقادیر رستر SAR (هدف): دامنه (amplitude)، شدت (intensity) یا دسی‌بل (db).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="196"/>
        <source>Lee speckle filter on the SAR image (the thesis).</source>
        <translation>فیلتر اسپکل لی روی تصویر SAR (طبق پایان‌نامه).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="197"/>
        <source>Lee window side, px (not given; 7).</source>
        <translation>اندازهٔ ضلع پنجرهٔ لی، px (ذکر نشده؛ ۷).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="198"/>
        <source>Equivalent number of looks of the SAR image (not given; 1).</source>
        <translation>تعداد نگاه معادل تصویر SAR (ذکر نشده؛ ۱).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="199"/>
        <source>GGS window shape alpha (Shui &amp; Cheng&apos;s practical setting).</source>
        <translation>پارامتر شکل alpha پنجرهٔ GGS (تنظیم عملی Shui &amp; Cheng).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="200"/>
        <source>GGS window width beta, px.</source>
        <translation>پهنای beta پنجرهٔ GGS، px.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="201"/>
        <source>GGS window length sigma_x, px (l_f = 13).</source>
        <translation>طول sigma_x پنجرهٔ GGS، px (l_f = 13).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="202"/>
        <source>GGS orientations P (not given; 8).</source>
        <translation>تعداد جهت‌های P در GGS (ذکر نشده؛ ۸).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="203"/>
        <source>Hysteresis low threshold on 1 - ratio (not given).</source>
        <translation>آستانهٔ پایین هیسترزیس روی مقدار ۱ منهای نسبت (ذکر نشده).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="204"/>
        <source>Hysteresis high threshold on 1 - ratio (not given).</source>
        <translation>آستانهٔ بالای هیسترزیس روی مقدار ۱ منهای نسبت (ذکر نشده).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="205"/>
        <source>Edge components smaller than this are removed (the thesis: 65).</source>
        <translation>مؤلفه‌های همبند لبه که کوچک‌تر از این مقدارند حذف می‌شوند (پایان‌نامه: ۶۵).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="206"/>
        <source>Radon peaks taken before clustering (not given; 40).</source>
        <translation>تعداد قله‌های رادون که پیش از خوشه‌بندی برداشته می‌شوند (ذکر نشده؛ ۴۰).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="207"/>
        <source>Radon angle step, degrees (MATLAB&apos;s default 1).</source>
        <translation>گام زاویهٔ رادون، درجه (پیش‌فرض MATLAB: ۱).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="208"/>
        <source>Fewest edge pixels on a line; 0 = Sui et al.&apos;s 15 px per 256 px of image side.</source>
        <translation>کمینهٔ تعداد پیکسل‌های لبه روی یک خط؛ ۰ = مقدار Sui et al.، یعنی ۱۵ px به ازای هر ۲۵۶ px از ضلع تصویر.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="209"/>
        <source>Lines closer than this in angle ... (not given; 5).</source>
        <translation>خطوطی که از نظر زاویه نزدیک‌تر از این مقدارند ... (ذکر نشده؛ ۵).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="210"/>
        <source>... and this in offset are one line (not given; 10).</source>
        <translation>... و از نظر فاصله از مبدأ نزدیک‌تر از این مقدار، یک خط به شمار می‌آیند (ذکر نشده؛ ۱۰).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="211"/>
        <source>Line pairs crossing at less than this are not intersected (Sui et al.).</source>
        <translation>نقطهٔ تقاطع زوج خط‌هایی که با زاویه‌ای کمتر از این مقدار یکدیگر را قطع می‌کنند محاسبه نمی‌شود (Sui et al.).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="235"/>
        <source>Eigenvector matching, VSPM, or their fusion (the thesis).</source>
        <translation>تناظریابی با بردار ویژه (eigenvector)، VSPM (vspm) یا تلفیق آن دو (fusion، طبق پایان‌نامه).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="213"/>
        <source>Fusion rule (not given): score-level sum, or cascade (VSPM&apos;s proximity inside eigenvector matching).</source>
        <translation>قاعدهٔ تلفیق (ذکر نشده): جمع در سطح امتیاز (score)، یا آبشاری (cascade: ماتریس مجاورت VSPM درون تناظریابی بردار ویژه).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="214"/>
        <source>Weight of the eigenvector score in the score-level fusion.</source>
        <translation>وزن امتیاز بردار ویژه در تلفیق در سطح امتیاز.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="215"/>
        <source>Eigenvector proximity sigma as a fraction of each point set&apos;s RMS spread (not given).</source>
        <translation>مقدار sigma مجاورت در تناظریابی بردار ویژه، به‌صورت کسری از پراکندگی RMS هر مجموعه نقطه (ذکر نشده).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="216"/>
        <source>VSPM proximity matrix: as printed (eq. 2-73), laplacian or gaussian.</source>
        <translation>ماتریس مجاورت VSPM: مطابق متن چاپ‌شده (printed، معادلهٔ 2-73)، لاپلاسی (laplacian) یا گوسی (gaussian).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="217"/>
        <source>Crossing angles of matched intersections differ by less (the thesis).</source>
        <translation>زاویه‌های برخورد در تقاطع‌های متناظر کمتر از این مقدار با هم اختلاف دارند (طبق پایان‌نامه).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="212"/>
        <source>Shapiro-Brady eigenvector matching alone (the thesis&apos;s baseline).</source>
        <translation>فقط تناظریابی بردار ویژهٔ Shapiro-Brady (روش پایهٔ پایان‌نامه).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="218"/>
        <source>VSPM alone (the thesis&apos;s baseline).</source>
        <translation>فقط VSPM (روش پایهٔ پایان‌نامه).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="106"/>
        <source>What the target raster holds when it is SAR: amplitude, intensity or db (other images: leave amplitude).</source>
        <translation>نوع مقادیر رستر هدف وقتی SAR است: دامنه (amplitude)، شدت (intensity) یا دسی‌بل (db)؛ برای سایر تصاویر همان amplitude بماند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="107"/>
        <source>No Lee filter: CFOG&apos;s smoothing already averages speckle, and the filter measured no gain (multimodal proxy 8/8 either way; real pairs 0.85 vs 1.06 px median).</source>
        <translation>بدون فیلتر لی: هموارسازی CFOG خودش اسپکل را میانگین می‌گیرد و فیلتر در سنجش‌ها بهبودی نشان نداد (مجموعهٔ جایگزین چندمدالیته در هر دو حالت ۸/۸؛ جفت‌های واقعی: میانهٔ ۰٫۸۵ در برابر ۱٫۰۶ px).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="108"/>
        <source>Coarse transform: exhaustive CFOG search (default: it registers where the thesis&apos;s 5-8 matches cannot) or the thesis&apos;s lines.</source>
        <translation>تبدیل تقریبی: جست‌وجوی کامل CFOG (search؛ پیش‌فرض: جایی ثبت می‌کند که ۵ تا ۸ تطابق روش پایان‌نامه از پس آن برنمی‌آیند) یا خطوط پایان‌نامه (lines).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="109"/>
        <source>Rotations searched, +- degrees (georeferenced targets arrive north-up, so rotation is small).</source>
        <translation>بازهٔ دوران‌های جست‌وجوشده، +- درجه (تصاویر هدف زمین‌مرجع‌شده شمال‌بالا هستند، پس دوران کوچک است).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="110"/>
        <source>Scales searched, 1/max_scale .. max_scale (2 registers the scale family&apos;s 0.5-2, 10/10 against 6/10 for 1.5, for 26 % more time on a 1000 px pair).</source>
        <translation>بازهٔ مقیاس‌های جست‌وجوشده، 1/max_scale .. max_scale (مقدار ۲ خانوادهٔ آزمون مقیاس با بازهٔ ۰٫۵ تا ۲ را ثبت می‌کند، ۱۰/۱۰ در برابر ۶/۱۰ برای ۱٫۵، به بهای ۲۶ % زمان بیشتر روی یک جفت ۱۰۰۰ px).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="111"/>
        <source>Longest reference side at the first search level, px.</source>
        <translation>طول بلندترین ضلع تصویر مرجع در نخستین سطح جست‌وجو، px.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="112"/>
        <source>The search compares descriptors minus their local mean over this many first-level px: with the global mean (0) regional orientation statistics favoured wrong axis-aligned candidates (overlap family 8/10; 3 px: 10/10, 6 px: 9/10).</source>
        <translation>جست‌وجو توصیفگرها را پس از کم کردن میانگین محلی‌شان در پنجره‌ای به این اندازه (px سطح اول) مقایسه می‌کند: با میانگین سراسری (۰)، آمار جهت‌های ناحیه‌ای به سود نامزدهای نادرستِ هم‌راستا با محورها عمل می‌کرد (خانوادهٔ همپوشانی ۸/۱۰؛ ۳ px: ۱۰/۱۰، ۶ px: ۹/۱۰).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="113"/>
        <source>Side of the CFOG templates, working px.</source>
        <translation>اندازهٔ ضلع الگوهای CFOG، px کاری.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="114"/>
        <source>Search radius of the first dense pass, working px (covers the coarse error).</source>
        <translation>شعاع جست‌وجوی نخستین گذر متراکم، px کاری (خطای تبدیل تقریبی را پوشش می‌دهد).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="115"/>
        <source>Weakest accepted template correlation; RANSAC removes the rest.</source>
        <translation>کمترین همبستگی پذیرفتنی برای الگو؛ RANSAC بقیه را حذف می‌کند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="116"/>
        <source>Templates per dense pass.</source>
        <translation>تعداد الگوها در هر گذر متراکم.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="117"/>
        <source>Coarse candidates checked by dense matching when the best is not convincing.</source>
        <translation>تعداد نامزدهای تقریبی که اگر بهترین نامزد قانع‌کننده نباشد، با تناظریابی متراکم بررسی می‌شوند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="120"/>
        <source>What the SAR raster holds: amplitude, intensity or db (complex is read as amplitude).</source>
        <translation>نوع مقادیر رستر SAR: دامنه (amplitude)، شدت (intensity) یا دسی‌بل (db)؛ دادهٔ مختلط به‌صورت دامنه خوانده می‌شود.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="121"/>
        <source>Scale space: nonlinear (the paper), gaussian or bilateral (baselines).</source>
        <translation>فضای مقیاس: غیرخطی (nonlinear، طبق مقاله)، گوسی (gaussian) یا دوسویه (bilateral) به‌عنوان روش‌های پایه.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="122"/>
        <source>Run on log amplitude, where speckle is additive and of one strength everywhere (not in the paper).</source>
        <translation>اجرا روی لگاریتم دامنه، که در آن اسپکل جمعی است و همه‌جا شدت یکسانی دارد (در مقاله نیست).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="123"/>
        <source>Gaussian pre-smoothing to sigma_0 before the diffusion, as KAZE does: on 1-look speckle it turns 3 of 24 failures into successes (the paper starts from the original image).</source>
        <translation>پیش‌هموارسازی گوسی تا sigma_0 پیش از پخش، همان‌گونه که KAZE انجام می‌دهد: روی اسپکل تک‌نگاه، ۳ مورد از ۲۴ شکست را به موفقیت تبدیل می‌کند (مقاله از تصویر اصلی شروع می‌کند).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="124"/>
        <source>Octaves O (the paper: 4).</source>
        <translation>تعداد اکتاوها، O (مقاله: ۴).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="125"/>
        <source>Sub-levels S per octave (the paper: 3; S + 3 images per octave).</source>
        <translation>تعداد زیرسطح‌ها در هر اکتاو، S (مقاله: ۳؛ S + 3 تصویر در هر اکتاو).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="126"/>
        <source>Base scale sigma_0 (gap; Lowe&apos;s 1.6).</source>
        <translation>مقیاس پایه، sigma_0 (نامشخص در مقاله؛ مقدار ۱٫۶ از Lowe).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="127"/>
        <source>ROEWA exponential weight alpha (gap; SAR-SIFT&apos;s 2).</source>
        <translation>وزن نمایی alpha در ROEWA (نامشخص در مقاله؛ مقدار ۲ از SAR-SIFT).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="128"/>
        <source>Contrast factor K = this percentile of the ROEWA gradient (gap; KAZE&apos;s 70).</source>
        <translation>ضریب کنتراست K = این صدک از گرادیان ROEWA (نامشخص در مقاله؛ مقدار ۷۰ از KAZE).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="129"/>
        <source>K is multiplied by this at each new octave (the paper: &apos;change K&apos;; AKAZE&apos;s 0.75).</source>
        <translation>ضریب K در هر اکتاو جدید در این مقدار ضرب می‌شود (مقاله: «change K»؛ مقدار ۰٫۷۵ از AKAZE).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="130"/>
        <source>Gradient inside the conductance: roewa (the paper) or difference.</source>
        <translation>گرادیان درون تابع رسانایی: roewa (طبق مقاله) یا تفاضلی (difference).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="131"/>
        <source>DoG contrast threshold on the [0, 1] amplitude (gap; Lowe&apos;s 0.03).</source>
        <translation>آستانهٔ کنتراست DoG روی دامنهٔ [0, 1] (نامشخص در مقاله؛ مقدار ۰٫۰۳ از Lowe).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="132"/>
        <source>DoG edge ratio r (Lowe&apos;s 10).</source>
        <translation>نسبت لبهٔ r در DoG (مقدار ۱۰ از Lowe).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="133"/>
        <source>Drop keypoints whose phase congruency is below pc_threshold (the paper).</source>
        <translation>حذف نقاط کلیدی‌ای که همدوسی فازشان کمتر از pc_threshold است (طبق مقاله).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="134"/>
        <source>Phase congruency threshold (the paper: 0.01).</source>
        <translation>آستانهٔ همدوسی فاز (مقاله: ۰٫۰۱).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="135"/>
        <source>Kovesi&apos;s noise multiplier k (gap; his default 2).</source>
        <translation>ضریب نویز k در روش Kovesi (نامشخص در مقاله؛ پیش‌فرض خود او: ۲).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="136"/>
        <source>Range sigma of the bilateral scale space on the [0, 1] amplitude (BFSIFT baseline; not given).</source>
        <translation>مقدار sigma برد (range) در فضای مقیاس دوسویه روی دامنهٔ [0, 1] (روش پایهٔ BFSIFT؛ ذکر نشده).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="137"/>
        <source>Ignore keypoints of the finest octave (BFSIFT does).</source>
        <translation>نادیده گرفتن نقاط کلیدی ریزترین اکتاو (کاری که BFSIFT می‌کند).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="138"/>
        <source>Nearest/second-nearest ratio (the paper: 0.8).</source>
        <translation>نسبت نزدیک‌ترین به دومین نزدیک‌ترین همسایه (مقاله: ۰٫۸).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="139"/>
        <source>One-way ratio test: dual ratio matching keeps too few matches on 1-look speckle, and RANSAC removes the extra outliers (the paper: dual-ratio).</source>
        <translation>آزمون نسبت یک‌طرفه: تناظریابی با نسبت دوطرفه روی اسپکل تک‌نگاه تطابق‌های بسیار کمی نگه می‌دارد و RANSAC نقاط پرت اضافی را حذف می‌کند (مقاله: dual-ratio).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="188"/>
        <source>Gaussian pre-smoothing to sigma_0 before the diffusion, as KAZE does (the paper starts from the original image).</source>
        <translation>پیش‌هموارسازی گوسی تا sigma_0 پیش از پخش، همان‌گونه که KAZE انجام می‌دهد (مقاله از تصویر اصلی شروع می‌کند).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="191"/>
        <source>Dual matching: both directions pass the ratio test (the paper).</source>
        <translation>تناظریابی دوطرفه: هر دو جهت باید از آزمون نسبت بگذرند (طبق مقاله).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="219"/>
        <source>NDSS+SIFT: the paper&apos;s ablation without phase congruency.</source>
        <translation>روش NDSS+SIFT: آزمایش حذفی مقاله، بدون همدوسی فاز.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="193"/>
        <source>Gaussian scale space (the paper&apos;s SIFT baseline).</source>
        <translation>فضای مقیاس گوسی (روش پایهٔ SIFT در مقاله).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="194"/>
        <source>No phase congruency in the baseline.</source>
        <translation>روش پایه از همدوسی فاز استفاده نمی‌کند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="187"/>
        <source>Bilateral-filter scale space (BFSIFT).</source>
        <translation>فضای مقیاس با فیلتر دوسویه (BFSIFT).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="189"/>
        <source>No phase congruency in BFSIFT.</source>
        <translation>روش BFSIFT از همدوسی فاز استفاده نمی‌کند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="190"/>
        <source>BFSIFT skips the finest scale.</source>
        <translation>روش BFSIFT ریزترین مقیاس را کنار می‌گذارد.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="220"/>
        <source>Strongest keypoints kept per image.</source>
        <translation>تعداد قوی‌ترین نقاط کلیدی که در هر تصویر نگه داشته می‌شوند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="221"/>
        <source>FAST corner threshold (OpenCV default).</source>
        <translation>آستانهٔ گوشه‌یابی FAST (پیش‌فرض OpenCV).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="222"/>
        <source>Pyramid levels, scale factor 1.2 (OpenCV default).</source>
        <translation>تعداد سطوح هرم، با ضریب مقیاس ۱٫۲ (پیش‌فرض OpenCV).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="223"/>
        <source>Nearest/second-nearest Hamming distance ratio.</source>
        <translation>نسبت فاصلهٔ همینگ نزدیک‌ترین به دومین نزدیک‌ترین همسایه.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="155"/>
        <source>Cross-check of matches: none, mutual or dual-ratio.</source>
        <translation>بررسی متقابل تطابق‌ها: بدون بررسی (none)، دوطرفه (mutual) یا نسبت دوطرفه (dual-ratio).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="224"/>
        <source>Strongest SIFT keypoints kept per image (0 = all).</source>
        <translation>تعداد قوی‌ترین نقاط کلیدی SIFT که در هر تصویر نگه داشته می‌شوند (۰ = همه).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="225"/>
        <source>Nearest/second-nearest distance ratio (as the SIFT baseline).</source>
        <translation>نسبت فاصلهٔ نزدیک‌ترین به دومین نزدیک‌ترین همسایه (مانند روش پایهٔ SIFT).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="226"/>
        <source>Correspondences per side of the grid that carries the shift.</source>
        <translation>تعداد نقاط تناظر در هر ضلع شبکه‌ای که جابه‌جایی به‌دست‌آمده را منتقل می‌کند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="227"/>
        <source>Lowest accepted normalised correlation peak.</source>
        <translation>کمترین قلهٔ همبستگی نرمال‌شدهٔ پذیرفتنی.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="228"/>
        <source>Strongest FAST corners kept per image (RIFT: 5000).</source>
        <translation>تعداد قوی‌ترین گوشه‌های FAST که در هر تصویر نگه داشته می‌شوند (RIFT: ۵۰۰۰).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="149"/>
        <source>Strongest CenSurE keypoints kept per image (the paper: 2500).</source>
        <translation>تعداد قوی‌ترین نقاط کلیدی CenSurE که در هر تصویر نگه داشته می‌شوند (مقاله: ۲۵۰۰).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="150"/>
        <source>Smallest |CenSurE response| in grey levels (gap: paper uses CenSurE defaults without values).</source>
        <translation>کمترین مقدار |پاسخ CenSurE| بر حسب سطح خاکستری (نامشخص در مقاله: مقاله از پیش‌فرض‌های CenSurE بدون ذکر مقدارشان استفاده می‌کند).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="151"/>
        <source>CenSurE&apos;s edge test limit on trace^2/det (Agrawal et al. 2008).</source>
        <translation>حد آزمون لبهٔ CenSurE روی trace^2/det (Agrawal et al. 2008).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="152"/>
        <source>Region radius = factor x half the outer octagon (gap in the paper).</source>
        <translation>شعاع ناحیه = ضریب × نصف هشت‌ضلعی بیرونی (نامشخص در مقاله).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="153"/>
        <source>Product: quadratic sub-pixel keypoint positions (CenSurE keeps whole pixels).</source>
        <translation>نسخهٔ محصول: موقعیت زیرپیکسلی نقاط کلیدی با برازش درجه دو (CenSurE موقعیت‌ها را در پیکسل‌های صحیح نگه می‌دارد).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="154"/>
        <source>Nearest/second-nearest distance ratio (gap: the paper&apos;s rule is not given).</source>
        <translation>نسبت فاصلهٔ نزدیک‌ترین به دومین نزدیک‌ترین همسایه (نامشخص در مقاله: قاعدهٔ مقاله ذکر نشده است).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="156"/>
        <source>LBP neighbour radius in region pixels (gap; the paper&apos;s figure shows 1; 2 keeps codes stable under keypoint and resampling jitter).</source>
        <translation>شعاع همسایگی LBP بر حسب پیکسل ناحیه (نامشخص در مقاله؛ شکل مقاله ۱ را نشان می‌دهد؛ مقدار ۲ کدها را در برابر لرزش موقعیت نقاط کلیدی و بازنمونه‌برداری پایدار نگه می‌دارد).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="157"/>
        <source>Product: Gaussian sigma (region pixels) before coding; the paper has none, and radius-1 codes on raw pixels flip on sensor noise.</source>
        <translation>نسخهٔ محصول: sigma گوسی (پیکسل ناحیه) پیش از کدگذاری؛ مقاله هموارسازی ندارد و کدهای شعاع ۱ روی پیکسل‌های خام با نویز حسگر وارونه می‌شوند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="158"/>
        <source>CS-LBP threshold T in grey levels (gap; 0 = exact gain/offset invariance).</source>
        <translation>آستانهٔ T در CS-LBP بر حسب سطح خاکستری (نامشخص در مقاله؛ ۰ = ناوردایی دقیق نسبت به بهره و آفست).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="159"/>
        <source>Ring weight: literal 1-(d/h)^2 (the paper) or border 1-(2d/h)^2.</source>
        <translation>وزن حلقه: literal با 1-(d/h)^2 (طبق مقاله) یا border با 1-(2d/h)^2.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="236"/>
        <source>Faithful: whole-pixel CenSurE positions, as the paper.</source>
        <translation>مطابق مقاله: موقعیت‌های CenSurE در پیکسل‌های صحیح، همان‌گونه که در مقاله آمده.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="237"/>
        <source>Faithful: radius 1, the paper&apos;s Fig. 1.</source>
        <translation>مطابق مقاله: شعاع ۱، طبق شکل ۱ مقاله.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="238"/>
        <source>Faithful: no smoothing, as the paper.</source>
        <translation>مطابق مقاله: بدون هموارسازی، همان‌گونه که در مقاله آمده.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="192"/>
        <source>Faithful: whole-pixel CenSurE positions, as in the paper&apos;s comparison.</source>
        <translation>مطابق مقاله: موقعیت‌های CenSurE در پیکسل‌های صحیح، همان‌گونه که در مقایسهٔ مقاله آمده.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="167"/>
        <source>Sobel magnitude threshold T (0..255; gap in the paper, default from a sweep).</source>
        <translation>آستانهٔ T برای بزرگی گرادیان سوبل (0..255؛ نامشخص در مقاله، پیش‌فرض از پویش مقادیر).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="168"/>
        <source>Hamming distance under which a keypoint with a near-duplicate in its own image is removed (gap; from a sweep).</source>
        <translation>فاصلهٔ همینگی که اگر نقطهٔ کلیدی در همان تصویر خودش نقطهٔ تقریباً تکراری با فاصلهٔ کمتر از آن داشته باشد، حذف می‌شود (نامشخص در مقاله؛ از پویش مقادیر).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="169"/>
        <source>Gradient magnitude: l1 = 0.5|Gx|+0.5|Gy| (OpenCV tutorial, the spec&apos;s reading) or l2 = sqrt(Gx^2+Gy^2)/sqrt(2), which does not change with edge direction.</source>
        <translation>بزرگی گرادیان: l1 = 0.5|Gx|+0.5|Gy| (آموزش OpenCV، برداشت سند مشخصات) یا l2 = sqrt(Gx^2+Gy^2)/sqrt(2) که با جهت لبه تغییر نمی‌کند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="170"/>
        <source>to-zero keeps magnitudes above T (the paper); soft subtracts T, so the edge image has no jumps at the threshold for the DoG to fire on.</source>
        <translation>حالت to-zero بزرگی‌های بالاتر از T را نگه می‌دارد (طبق مقاله)؛ حالت soft مقدار T را کم می‌کند تا تصویر لبه در آستانه پرشی نداشته باشد که DoG روی آن پاسخ دهد.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="171"/>
        <source>Resolution at which the DoG pyramid starts (2 = OpenCV SIFT&apos;s upsampled base, the paper&apos;s; 1 = full resolution, 4x less work).</source>
        <translation>تفکیک‌پذیری‌ای که هرم DoG از آن شروع می‌شود (۲ = پایهٔ بزرگ‌نمایی‌شدهٔ SIFT در OpenCV، همانند مقاله؛ ۱ = تفکیک‌پذیری کامل، با ۴ برابر محاسبهٔ کمتر).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="172"/>
        <source>Strongest DoG keypoints kept per image (0 = all, as the paper).</source>
        <translation>تعداد قوی‌ترین نقاط کلیدی DoG که در هر تصویر نگه داشته می‌شوند (۰ = همه، طبق مقاله).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="173"/>
        <source>SIFT DoG contrast threshold on the edge image (OpenCV default).</source>
        <translation>آستانهٔ کنتراست DoG در SIFT روی تصویر لبه (پیش‌فرض OpenCV).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="174"/>
        <source>Describe each keypoint on the pyramid level matching its SIFT size (the paper uses a fixed 31-px patch, which breaks beyond ~1.5x scale).</source>
        <translation>توصیف هر نقطهٔ کلیدی در سطحی از هرم که با اندازهٔ SIFT آن جور است (مقاله وصلهٔ ثابت ۳۱ px به کار می‌برد که در اختلاف مقیاس بیش از حدود ۱٫۵ برابر از کار می‌افتد).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="175"/>
        <source>Lowe ratio on Hamming distances (1 = off, as the paper).</source>
        <translation>نسبت Lowe روی فاصله‌های همینگ (۱ = غیرفعال، طبق مقاله).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="176"/>
        <source>Spec Appendix B (not in the paper): keep matches at the peaks of the angle and log-scale difference histograms.</source>
        <translation>پیوست B سند مشخصات (در مقاله نیست): نگه‌داشتن تطابق‌هایی که در قله‌های هیستوگرام‌های اختلاف زاویه و اختلاف لگاریتم مقیاس قرار دارند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="239"/>
        <source>Faithful: OpenCV tutorial magnitude 0.5|Gx|+0.5|Gy|.</source>
        <translation>مطابق مقاله: بزرگی گرادیان به روش آموزش OpenCV، یعنی 0.5|Gx|+0.5|Gy|.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="240"/>
        <source>Faithful: threshold-to-zero.</source>
        <translation>مطابق مقاله: آستانه‌گذاری به صفر (threshold-to-zero).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="241"/>
        <source>Faithful: OpenCV SIFT as is (upsampled base).</source>
        <translation>مطابق مقاله: SIFT در OpenCV بدون تغییر (پایهٔ بزرگ‌نمایی‌شده).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="242"/>
        <source>Faithful: every DoG keypoint.</source>
        <translation>مطابق مقاله: همهٔ نقاط کلیدی DoG.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="243"/>
        <source>Faithful: one 31-px patch at full resolution for every keypoint.</source>
        <translation>مطابق مقاله: یک وصلهٔ ۳۱ px در تفکیک‌پذیری کامل برای هر نقطهٔ کلیدی.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="244"/>
        <source>Faithful: mutual nearest neighbours without a ratio test.</source>
        <translation>مطابق مقاله: نزدیک‌ترین همسایه‌های دوطرفه بدون آزمون نسبت.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="231"/>
        <source>Strongest keypoints kept per image (0 = all).</source>
        <translation>تعداد قوی‌ترین نقاط کلیدی که در هر تصویر نگه داشته می‌شوند (۰ = همه).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="232"/>
        <source>DoG contrast threshold (OpenCV default, Lowe 2004).</source>
        <translation>آستانهٔ کنتراست DoG (پیش‌فرض OpenCV، Lowe 2004).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="233"/>
        <source>Edge-response ratio limit (Lowe 2004).</source>
        <translation>حد نسبت پاسخ لبه (Lowe 2004).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="234"/>
        <source>Lowe&apos;s nearest/second-nearest distance ratio.</source>
        <translation>نسبت فاصلهٔ نزدیک‌ترین به دومین نزدیک‌ترین همسایه (Lowe).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="179"/>
        <source>Longest reference side for feature extraction, px: enough detail for RIFT features, and their cost.</source>
        <translation>طول بلندترین ضلع تصویر مرجع برای استخراج ویژگی، px: تعادلی میان جزئیات کافی برای ویژگی‌های RIFT و هزینهٔ محاسبهٔ آن‌ها.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="180"/>
        <source>Pyramid levels (factors 2^-k/2) per image; 3 covers scales 1/2 to 2.</source>
        <translation>تعداد سطوح هرم (ضرایب 2^-k/2) برای هر تصویر؛ ۳ سطح، مقیاس‌های ۱/۲ تا ۲ را پوشش می‌دهد.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="181"/>
        <source>Keypoints kept at the first level (0.7 and 0.5 times that at the next two).</source>
        <translation>تعداد نقاط کلیدی نگه‌داشته‌شده در سطح اول (در دو سطح بعدی ۰٫۷ و ۰٫۵ برابر آن).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="182"/>
        <source>Rotation-scale hypotheses checked densely (10 gave nothing more).</source>
        <translation>تعداد فرضیه‌های دوران-مقیاس که به‌صورت متراکم بررسی می‌شوند (۱۰ فرضیه بهبودی بیشتری نداد).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="183"/>
        <source>Hypotheses refined by local RIFT (5 gave nothing more).</source>
        <translation>تعداد فرضیه‌هایی که با RIFT محلی پالایش می‌شوند (۵ فرضیه بهبودی بیشتری نداد).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="184"/>
        <source>Longest reference side for the dense check, px: keeps its 30 FFT trials per hypothesis cheap; where CFOG separated right from wrong poses best.</source>
        <translation>طول بلندترین ضلع تصویر مرجع برای بررسی متراکم، px: ۳۰ آزمایش FFT هر فرضیه را کم‌هزینه نگه می‌دارد؛ در این اندازه CFOG وضعیت‌های درست را بهتر از همه از وضعیت‌های نادرست جدا کرد.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="185"/>
        <source>Longest reference side for local RIFT matching, px.</source>
        <translation>طول بلندترین ضلع تصویر مرجع برای تناظریابی محلی RIFT، px.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="186"/>
        <source>Fewest local-RIFT inliers for a refined hypothesis.</source>
        <translation>کمترین تعداد نقاط سازگار (inlier) در RIFT محلی برای یک فرضیهٔ پالایش‌شده.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="86"/>
        <source>Output CRS (empty: the reference&apos;s)</source>
        <translation>سیستم مختصات خروجی (خالی: سیستم مختصات مرجع)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="89"/>
        <source>Output format</source>
        <translation>قالب خروجی</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="97"/>
        <source>Pixels outside the target</source>
        <translation>پیکسل‌های بیرون از هدف</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="161"/>
        <source>HTML files (*.html)</source>
        <translation>پرونده‌های HTML (*.html)</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="260"/>
        <source>GCP points are written to a GeoPackage: choose a .gpkg file (got &apos;{}&apos;).</source>
        <translation>نقاط کنترل در یک GeoPackage نوشته می‌شوند: یک پروندهٔ ‎.gpkg انتخاب کنید (داده‌شده: «{}»).</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="282"/>
        <source>Invalid parameter: {}</source>
        <translation>پارامتر نامعتبر: {}</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="265"/>
        <source>Hamta stopped on an unexpected error ({}: {}); no output was written. Please report it.</source>
        <translation type="obsolete">همتا با یک خطای پیش‌بینی‌نشده متوقف شد ({}: {})؛ هیچ خروجی‌ای نوشته نشد. لطفاً آن را گزارش کنید.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="92"/>
        <source>GeoTIFF (tiled, compressed)</source>
        <translation>GeoTIFF (کاشی‌بندی‌شده، فشرده)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="94"/>
        <source>Warped VRT (no pixels copied)</source>
        <translation>VRT تبدیل‌شده (بدون رونوشت پیکسل‌ها)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="100"/>
        <source>Alpha band</source>
        <translation>باند آلفا</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="101"/>
        <source>Nodata value</source>
        <translation>مقدار بی‌داده</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="91"/>
        <source>From the file name (.vrt or GeoTIFF)</source>
        <translation>از نام فایل (.vrt یا GeoTIFF)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="93"/>
        <source>Cloud-optimised GeoTIFF</source>
        <translation>GeoTIFF بهینه برای ابر (COG)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="99"/>
        <source>Automatic (nodata, NaN or an alpha band)</source>
        <translation>خودکار (nodata، NaN یا باند آلفا)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="13"/>
        <source>Linear (scale and shift per axis)</source>
        <translation>خطی (مقیاس و جابه‌جایی در هر محور)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="17"/>
        <source>RANSAC tolerance (working px)</source>
        <translation>رواداری RANSAC (پیکسل کاری)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="71"/>
        <source>Mode (most frequent: classes)</source>
        <translation>مد (پرتکرارترین: رده‌ها)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="72"/>
        <source>Maximum</source>
        <translation>بیشینه</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="73"/>
        <source>Minimum</source>
        <translation>کمینه</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="74"/>
        <source>Median</source>
        <translation>میانه</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="75"/>
        <source>First quartile</source>
        <translation>چارک اول</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="76"/>
        <source>Third quartile</source>
        <translation>چارک سوم</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="139"/>
        <source>Keep unverified results</source>
        <translation>نگه‌داشتن نتایج تأییدنشده</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="52"/>
        <source>Local (non-rigid) correction</source>
        <translation>اصلاح محلی (غیرصلب)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="58"/>
        <source>Pixel-to-pixel (reference not georeferenced)</source>
        <translation>پیکسل به پیکسل (مرجع بدون زمین‌مرجع)</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="161"/>
        <source>Quality report (HTML)</source>
        <translation>گزارش کیفیت (HTML)</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="314"/>
        <source>{} (set &apos;{}&apos;).</source>
        <translation>{} (گزینهٔ «{}» را فعال کنید).</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="347"/>
        <source>{}; self-reported RMSE {:.3f} px, leave-one-out RMS {} px (residuals of the fit, not its accuracy).</source>
        <translation>{}؛ RMSE گزارش‌شده از خود برازش {:.3f} px، RMS حذف تک‌نقطه {} px (باقی‌مانده‌های برازش، نه دقت آن).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="54"/>
        <source>Local window (reference px; 0: automatic)</source>
        <translation>پنجرهٔ محلی (پیکسل مرجع؛ ۰: خودکار)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="47"/>
        <source>Accuracy asked for (reference px)</source>
        <translation>دقت خواسته‌شده (پیکسل مرجع)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="42"/>
        <source>Target band to match</source>
        <translation>باند هدف برای تطبیق</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="83"/>
        <source>Output pixel size (output CRS units)</source>
        <translation>اندازهٔ پیکسل خروجی (واحد CRS خروجی)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="95"/>
        <source>GDAL creation options</source>
        <translation>گزینه‌های ساخت GDAL</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="70"/>
        <source>Average</source>
        <translation>میانگین</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="122"/>
        <source>References: {}</source>
        <translation>مراجع: {}</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="5"/>
        <source>transform model: similarity, affine, projective, polynomial-2, polynomial-3, tps, linear, auto (the method&apos;s, affine for most, or polynomial-2 where the points bend away from it and the check bounds its error more tightly)</source>
        <translation>مدل تبدیل: similarity، affine، projective، polynomial-2، polynomial-3، tps، linear، auto (مدل روش، برای بیشتر روش‌ها آفین؛ یا polynomial-2 آنجا که نقطه‌ها از آن خم می‌شوند و بررسی مستقل خطای آن را تنگ‌تر محدود می‌کند)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="6"/>
        <source>the method&apos;s, affine for most</source>
        <translation type="obsolete">پیش‌فرض روش؛ برای بیشتر روش‌ها آفین</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="16"/>
        <source>pixel budget of the images matched (larger rasters are read decimated, then refined at full resolution)</source>
        <translation>بودجهٔ پیکسل تصاویری که تناظریابی می‌شوند (رسترهای بزرگ‌تر کاهش‌یافته خوانده و سپس در تفکیک‌پذیری کامل پالایش می‌شوند)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="19"/>
        <source>the method&apos;s, 3 for most</source>
        <translation>پیش‌فرض روش؛ برای بیشتر روش‌ها ۳</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="21"/>
        <source>seed of every random choice (RANSAC, sampling, inside methods), for reproducible runs</source>
        <translation>بذر همهٔ انتخاب‌های تصادفی (RANSAC، نمونه‌برداری، درون روش‌ها)، برای اجراهای تکرارپذیر</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="23"/>
        <source>full-resolution refinement of the matches: auto refines when an image was decimated or the method asks for it</source>
        <translation>پالایش تناظرها در تفکیک‌پذیری کامل: حالت خودکار وقتی پالایش می‌کند که تصویری کاهش‌یافته خوانده شده باشد یا روش آن را بخواهد</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="28"/>
        <source>most GCPs kept (well spread) for the fit and the outputs</source>
        <translation>بیشترین تعداد نقاط کنترل (خوب‌پراکنده) که برای برازش و خروجی‌ها نگه داشته می‌شوند</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="29"/>
        <source>Fewest agreeing matches</source>
        <translation>کمترین تعداد تناظرهای سازگار</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="30"/>
        <source>fewest agreeing correspondences accepted as a registration (at least the model&apos;s minimum + 2)</source>
        <translation>کمترین تعداد تناظرهای سازگار که یک ثبت پذیرفته می‌شود (دست‌کم کمینهٔ مدل به‌علاوهٔ ۲)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="31"/>
        <source>the method&apos;s</source>
        <translation>پیش‌فرض روش</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="32"/>
        <source>Outlier rejection</source>
        <translation>حذف داده‌های پرت</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="33"/>
        <source>outlier rejection before the fit: ransac, none (fit every correspondence, as some papers do) or triplets (cluster the transforms of match triplets)</source>
        <translation>حذف داده‌های پرت پیش از برازش: ransac، none (برازش همهٔ تناظرها، چنان‌که برخی مقاله‌ها می‌کنند) یا triplets (خوشه‌بندی تبدیل‌های سه‌تایی‌های تناظر)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="34"/>
        <source>Seeded LO-RANSAC</source>
        <translation>LO-RANSAC با بذر ثابت</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="36"/>
        <source>Cluster the transforms of match triplets</source>
        <translation>خوشه‌بندی تبدیل‌های سه‌تایی‌های تناظر</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="38"/>
        <source>use the target&apos;s own georeferencing as a starting point (auto: when it overlaps the reference), or ignore it when it is wrong</source>
        <translation>زمین‌مرجع خود تصویر هدف را نقطهٔ شروع بگیر (خودکار: وقتی با مرجع هم‌پوشانی دارد)، یا وقتی نادرست است نادیده‌اش بگیر</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="43"/>
        <source>band of the target to match</source>
        <translation>باند تصویر هدف برای تناظریابی</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="44"/>
        <source>luminance of RGB, else band 1</source>
        <translation>روشنایی RGB، وگرنه باند ۱</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="48"/>
        <source>accuracy asked for, reference px: a result is verified only when the independent check bounds its error within this</source>
        <translation>دقت خواسته‌شده، پیکسل مرجع: نتیجه تنها وقتی تأیید می‌شود که بررسی مستقل خطایش را در این حد کران‌دار کند</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="49"/>
        <source>Time cap of &apos;auto&apos; (s)</source>
        <translation>سقف زمان «auto» (ثانیه)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="50"/>
        <source>seconds &apos;auto&apos; may spend: then the method running is stopped (the first, the fast path, always completes) and no further one starts</source>
        <translation type="obsolete">ثانیه‌هایی که «خودکار» می‌تواند صرف کند: پس از آن روشِ در حال اجرا متوقف می‌شود (نخستین روش، مسیر سریع، همیشه کامل می‌شود) و روش دیگری آغاز نمی‌شود</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="53"/>
        <source>after the global model, correct local (non-rigid) misalignment from shifts measured on a dense grid of windows; the model becomes a thin plate spline through the grid</source>
        <translation>پس از مدل سراسری، ناهم‌ترازی محلی (غیرصلب) را با جابه‌جایی‌های اندازه‌گیری‌شده روی شبکه‌ای متراکم از پنجره‌ها اصلاح کن؛ مدل به اسپلاین صفحهٔ نازکِ گذرنده از شبکه تبدیل می‌شود</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="55"/>
        <source>local correction window side, reference px (0: automatic, 64 px, or 96 px for methods that correlate structure across modalities; otherwise at least 16)</source>
        <translation>ضلع پنجرهٔ اصلاح محلی، پیکسل مرجع (۰: خودکار، ۶۴ پیکسل، یا ۹۶ پیکسل برای روش‌هایی که ساختار را میان حالت‌های تصویربرداری همبسته می‌کنند؛ در غیر این صورت دست‌کم ۱۶)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="64"/>
        <source>resampling of the warped output</source>
        <translation>بازنمونه‌برداری خروجی تبدیل‌شده</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="78"/>
        <source>output pixel grid: the reference&apos;s, the target&apos;s own resolution, auto (the reference&apos;s when the resolutions are within 10 %), or target: the target&apos;s pixels unchanged under a corrected geotransform (where the model is a shift and scale, in the reference CRS)</source>
        <translation>شبکهٔ پیکسلی خروجی: شبکهٔ مرجع، تفکیک‌پذیری خود تصویر هدف، خودکار (شبکهٔ مرجع وقتی تفکیک‌پذیری‌ها کمتر از ۱۰٪ اختلاف دارند)، یا هدف: پیکسل‌های تصویر هدف بی‌تغییر با زمین‌مرجع اصلاح‌شده (وقتی مدل جابه‌جایی و مقیاس است، در سامانهٔ مختصات مرجع)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="84"/>
        <source>output pixel size in output CRS units (overrides the grid&apos;s)</source>
        <translation>اندازهٔ پیکسل خروجی به واحد سامانهٔ مختصات خروجی (بر اندازهٔ شبکه مقدم است)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="85"/>
        <source>from the pixel grid</source>
        <translation>از شبکهٔ پیکسلی</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="87"/>
        <source>output CRS: EPSG:code, WKT or PROJ string</source>
        <translation>سامانهٔ مختصات خروجی: EPSG:کد، WKT یا رشتهٔ PROJ</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="88"/>
        <source>the reference&apos;s CRS</source>
        <translation>سامانهٔ مختصات مرجع</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="96"/>
        <source>GDAL creation options of the warped raster, KEY=VALUE (e.g. COMPRESS=ZSTD, PREDICTOR=2), added to and overriding Hamta&apos;s defaults for the format</source>
        <translation>گزینه‌های ساخت GDAL برای رستر تبدیل‌شده، به شکل KEY=VALUE (مثلاً COMPRESS=ZSTD، PREDICTOR=2)، افزوده به پیش‌فرض‌های همتا برای آن قالب و مقدم بر آن‌ها</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="102"/>
        <source>nodata value with fill &apos;nodata&apos;</source>
        <translation>مقدار nodata هنگام پرکردن با «nodata»</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="103"/>
        <source>the target&apos;s, else 0</source>
        <translation>مقدار تصویر هدف، وگرنه ۰</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="230"/>
        <source>Registers the target raster onto the reference raster automatically: OpenCV SIFT keypoints, Lowe&apos;s ratio test with a mutual check, seeded RANSAC, full-resolution refinement, and the chosen transformation fitted on well-spread GCPs. Writes the georeferenced raster, the GCPs as a point layer and, on request, a QGIS Georeferencer .points file, a VRT carrying the GCPs and a JSON report.</source>
        <translation>رستر هدف را به‌طور خودکار روی رستر مرجع ثبت می‌کند: نقاط کلیدی SIFT از OpenCV، آزمون نسبت لو با بررسی دوطرفه، RANSAC با بذر ثابت، پالایش در تفکیک‌پذیری کامل، و برازش تبدیل انتخاب‌شده روی نقاط کنترلِ خوب‌پراکنده. رستر زمین‌مرجع‌شده و نقاط کنترل را به‌صورت لایه نقطه‌ای می‌نویسد و در صورت درخواست، پرونده .points برای Georeferencer کیوجی‌آی‌اس، یک VRT همراه نقاط کنترل و گزارشی به قالب JSON.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="105"/>
        <source>Registers a SAR image (the target) onto an optical reference, where intensities do not correspond and contrast is often inverted: an exhaustive search over rotation (up to 30 degrees either way), scale (up to 2 times either way) and shift on CFOG structural descriptors (gradient orientations, blind to the sign of contrast), then CFOG template matching on a regular grid, seeded RANSAC, the chosen transformation on well-spread GCPs, and full-resolution refinement of decimated images with the same similarity. Widen the rotation range for targets that are not roughly north-up. The CLI method &apos;lines-spectral-faithful&apos; is the thesis&apos;s line-intersection matcher as written (Radon lines, eigenvector and Voronoi/Hausdorff spectral matching), which rarely finds enough correct matches to register.</source>
        <translation>تصویر SAR (هدف) را روی تصویر نوری مرجع ثبت می‌کند، جایی که شدت‌ها با هم متناظر نیستند و کنتراست اغلب وارونه است: جست‌وجوی کامل روی دوران (تا ۳۰ درجه به هر سو)، مقیاس (تا ۲ برابر به هر سو) و جابه‌جایی با توصیفگرهای ساختاری CFOG (جهت‌های گرادیان، بی‌اعتنا به علامت کنتراست)، سپس تطبیق الگوی CFOG روی یک شبکهٔ منظم، RANSAC با بذر ثابت، برازش تبدیل انتخاب‌شده روی نقاط کنترل زمینی خوب‌پراکنده، و پالایش تصاویر کاهش‌یافته با تفکیک کامل با همان معیار شباهت. برای تصاویر هدفی که تقریباً شمال‌بالا نیستند، بازهٔ دوران را بزرگ‌تر کنید. روش «lines-spectral-faithful» در خط فرمان تناظریاب نقاط تقاطع خطوطِ پایان‌نامه به همان صورت نوشته‌شده است (خطوط رادون، تناظریابی طیفی با بردارهای ویژه و ورونوی/هاسدورف) که به‌ندرت تناظرهای درست کافی برای ثبت پیدا می‌کند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="119"/>
        <source>Registers a SAR image onto a SAR reference (another date, band or polarisation) despite speckle: a nonlinear diffusion scale space whose conductance uses the speckle-robust ROEWA gradient, SIFT keypoints and descriptors on it, keypoints kept only where phase congruency shows real structure, ratio-test matching, seeded RANSAC, then correlation refinement on a grid at full resolution. Set what the rasters hold (amplitude, intensity or dB; complex data is read as amplitude). Product defaults pre-smooth and use a one-way ratio test; the CLI method &apos;ndsift-pc-faithful&apos; is the paper as written.</source>
        <translation>تصویر SAR را با وجود اسپکل روی تصویر SAR مرجع (تاریخ، باند یا قطبش دیگر) ثبت می‌کند: فضای مقیاس پخش غیرخطی که رسانایی آن از گرادیان ROEWA مقاوم در برابر اسپکل استفاده می‌کند، نقاط کلیدی و توصیفگرهای SIFT روی آن، نگه‌داشتن نقاط کلیدی فقط جایی که همدوسی فاز ساختار واقعی نشان می‌دهد، تناظریابی با آزمون نسبت، RANSAC با بذر ثابت، سپس پالایش همبستگی روی یک شبکه با تفکیک کامل. تعیین کنید رسترها چه چیزی دارند (دامنه، شدت یا دسی‌بل؛ داده‌های مختلط به‌صورت دامنه خوانده می‌شوند). پیش‌فرض‌های محصول پیش‌هموارسازی می‌کنند و آزمون نسبت یک‌طرفه به کار می‌برند؛ روش «ndsift-pc-faithful» در خط فرمان نسخهٔ مطابق مقاله است.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="148"/>
        <source>Registers an optical satellite image onto a reference with any rotation between them: CenSurE octagon keypoints described by the rotation-invariant LBP descriptor (rings, intensity-order sub-regions, centre-symmetric LBP in each pixel&apos;s radial frame; no orientation step), mutual ratio-test matching, seeded RANSAC and the chosen transformation fitted on well-spread GCPs. Product defaults add sub-pixel keypoints and smoothed, radius-2 codes; the CLI method &apos;rilbp-faithful&apos; is the paper as written.</source>
        <translation>تصویر ماهواره‌ای اپتیکی را با هر مقدار دوران نسبت به مرجع ثبت می‌کند: نقاط کلیدی CenSurE با فیلترهای هشت‌ضلعی که با توصیفگر الگوی باینری محلی مستقل از دوران توصیف می‌شوند (حلقه‌ها، زیرنواحی مبتنی بر ترتیب شدت، LBP متقارن مرکزی در دستگاه مختصات شعاعی هر پیکسل؛ بدون مرحلهٔ تعیین جهت)، تناظریابی دوطرفه با آزمون نسبت، RANSAC با بذر ثابت و برازش تبدیل انتخاب‌شده روی نقاط کنترلِ خوب‌پراکنده. پیش‌فرض‌های محصول، نقاط کلیدی زیرپیکسلی و کدهای هموارشده با شعاع ۲ را می‌افزایند؛ روش «rilbp-faithful» در خط فرمان نسخهٔ مطابق مقاله است.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="166"/>
        <source>Registers an aerial (or any optical) image onto a satellite reference quickly: SIFT difference-of-Gaussian keypoints detected on a thresholded Sobel edge image, rBRIEF binary descriptors steered by the intensity centroid, removal of self-similar keypoints, mutual Hamming matching and RANSAC with affine samples. Few, strong keypoints make it several times faster than SIFT. Product defaults describe each keypoint at its own scale and add a ratio test; the CLI method &apos;sibrif-faithful&apos; is the paper as written.</source>
        <translation>تصویر هوایی (یا هر تصویر اپتیکی) را به‌سرعت روی تصویر ماهواره‌ای مرجع ثبت می‌کند: نقاط کلیدی تفاضل گوسی SIFT که روی تصویر لبهٔ آستانه‌گذاری‌شدهٔ سوبل آشکار می‌شوند، توصیفگرهای دودویی rBRIEF که با مرکز ثقل شدت جهت‌دهی می‌شوند، حذف نقاط کلیدی خودمشابه، تناظریابی دوطرفه با فاصلهٔ همینگ و RANSAC با نمونه‌های آفین. نقاط کلیدی کم‌شمار و قوی آن را چند برابر سریع‌تر از SIFT می‌کنند. پیش‌فرض‌های محصول هر نقطه را در مقیاس خودش توصیف می‌کنند و آزمون نسبت را می‌افزایند؛ روش «sibrif-faithful» در خط فرمان نسخهٔ مطابق مقاله است.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="178"/>
        <source>Registers a target of another modality than the reference (SAR, infrared, a depth rendering, a web map, night lights onto optical imagery) at any rotation and at scales from 1/2 to 2: phase-congruency (RIFT) features vote for rotation and scale, each hypothesis is checked densely with CFOG structural descriptors, the best are refined by matching RIFT descriptors near their predicted positions, and the result is refined at full resolution with CFOG and checked independently. Its baseline, the published RIFT2 matcher, is the CLI method &apos;rift&apos;.</source>
        <translation>تصویر هدفی با مدالیته‌ای متفاوت از مرجع (SAR، فروسرخ، رندر عمق، نقشهٔ وب، نورهای شبانه روی تصاویر نوری) را با هر دوران و در مقیاس‌های ۱/۲ تا ۲ ثبت می‌کند: ویژگی‌های همدوسی فاز (RIFT) به دوران و مقیاس رأی می‌دهند، هر فرضیه به‌صورت متراکم با توصیفگرهای ساختاری CFOG بررسی می‌شود، بهترین فرضیه‌ها با تناظریابی توصیفگرهای RIFT در نزدیکی موقعیت‌های پیش‌بینی‌شده‌شان پالایش می‌شوند، و نتیجه در تفکیک‌پذیری کامل با CFOG پالایش و به‌طور مستقل بررسی می‌شود. روش پایهٔ آن، یعنی تناظریاب منتشرشدهٔ RIFT2، روش «rift» در خط فرمان است.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="18"/>
        <source>outlier threshold, working pixels</source>
        <translation>آستانهٔ داده‌های پرت، پیکسل کاری</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="35"/>
        <source>None: fit every correspondence</source>
        <translation>هیچ: برازش همهٔ تناظرها</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="46"/>
        <source>band of the reference to match</source>
        <translation>باند تصویر مرجع برای تناظریابی</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="56"/>
        <source>Local grid spacing (reference px; 0: auto)</source>
        <translation>فاصلهٔ شبکهٔ محلی (پیکسل مرجع؛ ۰: خودکار)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="57"/>
        <source>local correction grid spacing, reference px (0: automatic, about 2000 windows over the overlap)</source>
        <translation>فاصلهٔ شبکهٔ اصلاح محلی، پیکسل مرجع (۰: خودکار، حدود ۲۰۰۰ پنجره روی ناحیهٔ هم‌پوشانی)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="59"/>
        <source>pixel-to-pixel registration onto a reference without georeferencing: its pixel grid stands in for the map and the outputs carry no CRS (without this, such a reference is refused)</source>
        <translation>ثبت پیکسل‌به‌پیکسل روی مرجعی بدون زمین‌مرجع: شبکهٔ پیکسلی آن جای نقشه را می‌گیرد و خروجی‌ها سامانهٔ مختصات ندارند (بدون این گزینه چنین مرجعی پذیرفته نمی‌شود)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="90"/>
        <source>warped raster: gtiff (tiled, DEFLATE), cog (cloud-optimised, with overviews) or vrt (a warped VRT reading the target, written as registered.vrt)</source>
        <translation>رستر تبدیل‌شده: gtiff (کاشی‌شده، DEFLATE)، cog (بهینه برای ابر، با نماهای کلی) یا vrt (یک VRT تبدیل‌شده که تصویر هدف را می‌خواند، با نام registered.vrt)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="98"/>
        <source>how pixels outside the target are marked: auto (the target&apos;s nodata or collar value, NaN for floats, else an alpha band, so valid zeros stay valid), alpha, or nodata</source>
        <translation>نحوهٔ علامت‌گذاری پیکسل‌های بیرون از تصویر هدف: خودکار (مقدار nodata یا حاشیهٔ هدف، NaN برای اعداد اعشاری، وگرنه باند آلفا، تا صفرهای معتبر معتبر بمانند)، alpha یا nodata</translation>
    </message>
    <message>
        <location filename="../processing/options.py" line="59"/>
        <source>empty</source>
        <translation>خالی</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="133"/>
        <source>Reference raster or map layer (XYZ, WMS...)</source>
        <translation type="obsolete">رستر یا لایهٔ نقشهٔ مرجع (XYZ، WMS...)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="60"/>
        <source>Search area</source>
        <translation>محدودهٔ جست‌وجو</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="61"/>
        <source>where to look for a target without usable georeferencing: xmin,ymin,xmax,ymax with an optional CRS after a comma (default CRS: the reference&apos;s, longitude and latitude for a map service)</source>
        <translation>جایی که هدفِ بی‌زمین‌مرجعِ قابل‌استفاده جست‌وجو می‌شود: xmin,ymin,xmax,ymax و در صورت نیاز سامانهٔ مختصات پس از یک ویرگول (پیش‌فرض: سامانهٔ مرجع، و برای سرویس نقشه طول و عرض جغرافیایی)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="62"/>
        <source>the whole reference; required with a map service</source>
        <translation>همهٔ مرجع؛ برای سرویس نقشه الزامی است</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="323"/>
        <source>on</source>
        <translation>روشن</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="341"/>
        <source>May help: {} ({}).</source>
        <translation>شاید کمک کند: {} ({}).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="82"/>
        <source>Target&apos;s own pixels (not resampled)</source>
        <translation>پیکسل‌های خود تصویر هدف (بدون بازنمونه‌برداری)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="160"/>
        <source>Windows per side of the grid over the overlap.</source>
        <translation>تعداد پنجره‌ها در هر ضلع شبکه روی ناحیهٔ هم‌پوشانی.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="163"/>
        <source>Share of a window&apos;s pixels that must be valid in both images.</source>
        <translation>سهمی از پیکسل‌های پنجره که باید در هر دو تصویر معتبر باشد.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="164"/>
        <source>Lowest accepted phase-correlation peak of a window.</source>
        <translation>کمترین قلهٔ پذیرفتنی همبستگی فاز در یک پنجره.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="245"/>
        <source>Strongest keypoints kept per image (XFeat&apos;s default).</source>
        <translation>تعداد قوی‌ترین نقاط کلیدی نگه‌داشته در هر تصویر (پیش‌فرض XFeat).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="246"/>
        <source>Cosine similarity a mutual nearest neighbour needs (XFeat&apos;s default).</source>
        <translation>شباهت کسینوسی لازم برای نزدیک‌ترین همسایهٔ دوسویه (پیش‌فرض XFeat).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="247"/>
        <source>Turns of the target tried, either way, in steps of 45 degrees: 0 when the target is upright on the reference (resampled onto it by its georeferencing), 180 for any rotation.</source>
        <translation>چرخش‌های آزموده‌شدهٔ تصویر هدف در هر دو سو، با گام ۴۵ درجه: ۰ وقتی هدف روی مرجع راست ایستاده است (با زمین‌مرجع خودش روی آن بازنمونه‌برداری شده)، ۱۸۰ برای هر چرخشی.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="248"/>
        <source>Both images are matched shrunk alike to at most this many pixels each: XFeat describes at an eighth of the resolution it is given, and the full-resolution refinement restores the precision (four times faster than at the 4 Mpx working size).</source>
        <translation>هر دو تصویر به یک نسبت تا حداکثر این تعداد پیکسل کوچک و سپس تطبیق داده می‌شوند: XFeat در یک‌هشتم تفکیک‌پذیری ورودی توصیف می‌کند و پالایش با تفکیک‌پذیری کامل دقت را بازمی‌گرداند (چهار برابر سریع‌تر از اندازهٔ کاری ۴ مگاپیکسل).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="161"/>
        <source>Side of each correlation window, working px (halved for small overlaps).</source>
        <translation>ضلع هر پنجرهٔ همبستگی، به پیکسل کاری (برای هم‌پوشانی‌های کوچک نصف می‌شود).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="162"/>
        <source>Longest side of the coarse whole-overlap correlation, px.</source>
        <translation>بلندترین ضلع همبستگی درشت کل ناحیهٔ هم‌پوشانی، به پیکسل.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="6"/>
        <source>automatic</source>
        <translation>خودکار</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="14"/>
        <source>Automatic (chosen by the check)</source>
        <translation>خودکار (به انتخاب بررسی مستقل)</translation>
    </message>
    <message>
        <location filename="../processing/catalogue.py" line="33"/>
        <source>Georeference a scanned map by its grid</source>
        <translation>زمین‌مرجع کردن نقشهٔ اسکن‌شده با شبکهٔ آن</translation>
    </message>
    <message>
        <location filename="../processing/catalogue.py" line="33"/>
        <source>Georeferences a scanned map sheet by the grid or graticule printed on it, without a reference layer. Place two or three crossings of the printed lines roughly in the QGIS Georeferencer, type their coordinates as printed (degrees, or metres of the national grid) and save the GCP points (.points); choose the sheet&apos;s CRS. Hamta finds the printed lattice as a whole, then every crossing of the sheet to a fraction of a pixel; each crossing becomes a GCP. The model (affine, or a polynomial where the projection bends the lines) is checked by predicting each grid line from the others: a result is verified only when that check is within the accuracy asked for, in scan pixels. A sheet whose grid cannot be found is refused, saying why.</source>
        <translation type="obsolete">برگهٔ نقشهٔ اسکن‌شده را با شبکه یا شبکهٔ جغرافیایی چاپ‌شده روی آن، بدون لایهٔ مرجع، زمین‌مرجع می‌کند. دو یا سه تقاطع خطوط چاپ‌شده را تقریبی در زمین‌مرجع‌ساز QGIS بگذارید، مختصاتشان را همان‌طور که چاپ شده بنویسید (درجه، یا متر شبکهٔ ملی) و نقاط کنترل (.points) را ذخیره کنید؛ CRS برگه را انتخاب کنید. همتا ابتدا کل شبکهٔ چاپ‌شده و سپس هر تقاطع برگه را با دقت کسری از پیکسل پیدا می‌کند؛ هر تقاطع یک نقطهٔ کنترل می‌شود. مدل (آفین، یا چندجمله‌ای جایی که تصویر نقشه خطوط را خم می‌کند) با پیش‌بینی هر خط شبکه از روی بقیه سنجیده می‌شود: نتیجه فقط وقتی تأیید می‌شود که این سنجش در دقت خواسته‌شده، به پیکسل اسکن، باشد. برگه‌ای که شبکه‌اش پیدا نشود، با گفتن دلیل، رد می‌شود.</translation>
    </message>
    <message>
        <location filename="../processing/catalogue.py" line="33"/>
        <source>Georeferences a scanned map sheet by the grid or graticule printed on it, without a reference layer. Choose the sheet&apos;s CRS. The coordinates printed in its margins are read (Tesseract); where they cannot be, place two or three crossings of the printed lines roughly in the QGIS Georeferencer, type their coordinates as printed (degrees, or metres of the national grid) and save the GCP points (.points) as hints. Hamta finds the printed lattice as a whole, then every crossing of the sheet to a fraction of a pixel; each crossing becomes a GCP. The model (affine, a polynomial where the projection bends the lines, a thin plate spline where the paper is warped) is checked by predicting each grid line from the others: a result is verified only when that check is within the accuracy asked for, in scan pixels. A sheet whose grid cannot be found is refused, saying why.</source>
        <translation>برگهٔ نقشهٔ اسکن‌شده را با شبکه یا شبکهٔ جغرافیایی چاپ‌شده روی آن، بدون لایهٔ مرجع، زمین‌مرجع می‌کند. CRS برگه را انتخاب کنید. مختصات چاپ‌شده در حاشیهٔ آن خوانده می‌شود (Tesseract)؛ جایی که خوانده نشود، دو یا سه تقاطع خطوط چاپ‌شده را تقریبی در زمین‌مرجع‌ساز QGIS بگذارید، مختصاتشان را همان‌طور که چاپ شده بنویسید (درجه، یا متر شبکهٔ ملی) و نقاط کنترل (.points) را به‌عنوان راهنما ذخیره کنید. همتا ابتدا کل شبکهٔ چاپ‌شده و سپس هر تقاطع برگه را با دقت کسری از پیکسل پیدا می‌کند؛ هر تقاطع یک نقطهٔ کنترل می‌شود. مدل (آفین، چندجمله‌ای جایی که تصویر نقشه خطوط را خم می‌کند، یا اسپلاین صفحهٔ نازک جایی که کاغذ تاب برداشته) با پیش‌بینی هر خط شبکه از روی بقیه سنجیده می‌شود: نتیجه فقط وقتی تأیید می‌شود که این سنجش در دقت خواسته‌شده، به پیکسل اسکن، باشد. برگه‌ای که شبکه‌اش پیدا نشود، با گفتن دلیل، رد می‌شود.</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="136"/>
        <source>Reference layer (raster, XYZ, WMS, areas or lines)</source>
        <translation>لایهٔ مرجع (رستر، XYZ، WMS، سطوح یا خطوط)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="143"/>
        <source>Smallest region kept, working px.</source>
        <translation>کوچک‌ترین ناحیهٔ نگه‌داشته‌شده، پیکسل کاری.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="146"/>
        <source>At most this many target regions, the largest, score a similarity: a bound on the search&apos;s time where a scan holds tens of thousands (letters, specks).</source>
        <translation>حداکثر این تعداد از نواحی هدف، بزرگ‌ترین‌ها، یک تبدیل شباهت را امتیاز می‌دهند: حدی بر زمان جست‌وجو وقتی یک اسکن ده‌ها هزار ناحیه (حروف، لکه‌ها) دارد.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="140"/>
        <source>Register a scanned map onto a layer of areas (regions)</source>
        <translation>ثبت نقشهٔ اسکن‌شده روی لایه‌ای از سطوح (نواحی)</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="141"/>
        <source>Registers a target whose closed shapes (lakes, blocks, fields) the reference shows too, in another look: a scanned map onto a layer of the areas it shows (a vector layer of water or buildings, drawn as a raster), at any rotation and scale. The regions of each image, cut at many grey levels, are matched by where they lie together; their centroids are refined at full resolution with CFOG and the result checked independently.</source>
        <translation>هدفی را ثبت می‌کند که شکل‌های بستهٔ آن (دریاچه‌ها، بلوک‌ها، زمین‌ها) در مرجع هم، با ظاهری دیگر، دیده می‌شوند: نقشهٔ اسکن‌شده روی لایه‌ای از سطوحی که نشان می‌دهد (لایهٔ برداری آب یا ساختمان‌ها که به رستر کشیده می‌شود)، در هر چرخش و مقیاسی. نواحی هر تصویر، که در سطوح خاکستری بسیاری بریده می‌شوند، بر پایهٔ جای قرارگیری‌شان در کنار هم تطبیق داده می‌شوند؛ مرکزهای آن‌ها با CFOG در تفکیک کامل پالایش می‌شوند و نتیجه به‌طور مستقل بررسی می‌شود.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="142"/>
        <source>Grey levels (percentiles) at which regions are cut from each image.</source>
        <translation>سطوح خاکستری (صدک‌ها) که نواحی هر تصویر در آن‌ها بریده می‌شوند.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="144"/>
        <source>Each image is matched at most this size (the larger of the two is brought to the smaller&apos;s pixel count first).</source>
        <translation>هر تصویر حداکثر در این اندازه تطبیق داده می‌شود (بزرگ‌تر از آن دو ابتدا به تعداد پیکسل کوچک‌تر رسانده می‌شود).</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="145"/>
        <source>Largest target regions each paired with every large reference region to propose a similarity.</source>
        <translation>بزرگ‌ترین نواحی هدف، که هر یک با هر ناحیهٔ بزرگ مرجع جفت می‌شود تا یک تبدیل شباهت پیشنهاد شود.</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="244"/>
        <source>Hamta stopped on an unexpected error ({}: {}); no output was written. Please report it (the traceback is in the log, tab Hamta).</source>
        <translation>Hamta با خطایی پیش‌بینی‌نشده متوقف شد ({}: {})؛ هیچ خروجی‌ای نوشته نشد. لطفاً گزارشش کنید (ردگیری خطا در گزارش‌ها، زبانهٔ Hamta، است).</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="272"/>
        <source> What was read and tried: {}</source>
        <translation> آنچه خوانده و آزموده شد: {}</translation>
    </message>
    <message>
        <location filename="../processing/register_algorithm.py" line="336"/>
        <source>Verified by an independent check: {}; estimated error within {}.</source>
        <translation>با بررسی مستقل تأیید شد: {}؛ خطای برآوردشده حداکثر {}.</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="50"/>
        <source>a cap on the seconds &apos;auto&apos; and a basemap search may spend: then the method running is stopped (the first, the fast path, always completes) and no further method or place starts. Without it what they try is bounded by counts (methods, places, requests), so the verdict is the same on any machine and under any load; with it, a slower or busier machine may try less</source>
        <translation>سقفی بر ثانیه‌هایی که «auto» و جست‌وجو در نقشهٔ پایه می‌توانند صرف کنند: پس از آن روش در حال اجرا متوقف می‌شود (اولی، مسیر سریع، همیشه کامل می‌شود) و هیچ روش یا محل دیگری آغاز نمی‌شود. بی آن، آنچه آزموده می‌شود با شمارش‌ها (روش‌ها، محل‌ها، درخواست‌ها) محدود است، پس حکم روی هر دستگاه و زیر هر باری یکی است؛ با آن، دستگاهی کندتر یا پرکارتر ممکن است کمتر بیازماید</translation>
    </message>
    <message>
        <location filename="core_strings.py" line="51"/>
        <source>no cap</source>
        <translation>بدون سقف</translation>
    </message>
</context>
</TS>
