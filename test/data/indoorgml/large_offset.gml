<?xml version="1.0" encoding="UTF-8"?>
<IndoorFeatures xmlns="http://www.opengis.net/indoorgml/1.0/core" xmlns:gml="http://www.opengis.net/gml/3.2" xmlns:xlink="http://www.w3.org/1999/xlink" gml:id="IF">
<primalSpaceFeatures><PrimalSpaceFeatures gml:id="PS"><cellSpaceMember><CellSpace gml:id="U1"><cellSpaceGeometry><Geometry3D>
<gml:Solid gml:id="S1" srsName="EPSG:25832"><gml:exterior><gml:Shell>
<gml:surfaceMember><gml:Polygon gml:id="U-floor"><gml:exterior><gml:LinearRing>
<gml:pos>500123.25 5400456.5 250.0</gml:pos>
<gml:pos>500123.25 5400459.5 250.0</gml:pos>
<gml:pos>500127.25 5400459.5 250.0</gml:pos>
<gml:pos>500127.25 5400456.5 250.0</gml:pos>
<gml:pos>500123.25 5400456.5 250.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="U-ceil"><gml:exterior><gml:LinearRing>
<gml:pos>500123.25 5400456.5 252.75</gml:pos>
<gml:pos>500127.25 5400456.5 252.75</gml:pos>
<gml:pos>500127.25 5400459.5 252.75</gml:pos>
<gml:pos>500123.25 5400459.5 252.75</gml:pos>
<gml:pos>500123.25 5400456.5 252.75</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="U-south"><gml:exterior><gml:LinearRing>
<gml:pos>500123.25 5400456.5 250.0</gml:pos>
<gml:pos>500127.25 5400456.5 250.0</gml:pos>
<gml:pos>500127.25 5400456.5 252.75</gml:pos>
<gml:pos>500123.25 5400456.5 252.75</gml:pos>
<gml:pos>500123.25 5400456.5 250.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="U-north"><gml:exterior><gml:LinearRing>
<gml:pos>500123.25 5400459.5 250.0</gml:pos>
<gml:pos>500123.25 5400459.5 252.75</gml:pos>
<gml:pos>500127.25 5400459.5 252.75</gml:pos>
<gml:pos>500127.25 5400459.5 250.0</gml:pos>
<gml:pos>500123.25 5400459.5 250.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="U-west"><gml:exterior><gml:LinearRing>
<gml:pos>500123.25 5400456.5 250.0</gml:pos>
<gml:pos>500123.25 5400456.5 252.75</gml:pos>
<gml:pos>500123.25 5400459.5 252.75</gml:pos>
<gml:pos>500123.25 5400459.5 250.0</gml:pos>
<gml:pos>500123.25 5400456.5 250.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="U-east"><gml:exterior><gml:LinearRing>
<gml:pos>500127.25 5400456.5 250.0</gml:pos>
<gml:pos>500127.25 5400459.5 250.0</gml:pos>
<gml:pos>500127.25 5400459.5 252.75</gml:pos>
<gml:pos>500127.25 5400456.5 252.75</gml:pos>
<gml:pos>500127.25 5400456.5 250.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
</gml:Shell></gml:exterior></gml:Solid>
</Geometry3D></cellSpaceGeometry></CellSpace></cellSpaceMember></PrimalSpaceFeatures></primalSpaceFeatures></IndoorFeatures>
