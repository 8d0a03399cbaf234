<?xml version="1.0" encoding="UTF-8"?>
<IndoorFeatures xmlns="http://www.opengis.net/indoorgml/1.0/core" xmlns:gml="http://www.opengis.net/gml/3.2" xmlns:xlink="http://www.w3.org/1999/xlink" gml:id="IF">
<primalSpaceFeatures><PrimalSpaceFeatures gml:id="PS">
<cellSpaceMember><CellSpace gml:id="R1"><gml:name>Room 1</gml:name>
<Geometry3D>
<gml:Solid gml:id="S1" srsDimension="3"><gml:exterior><gml:Shell>
<gml:surfaceMember><gml:Polygon gml:id="R1-floor"><gml:exterior><gml:LinearRing><gml:posList>0.0 0.0 0.0 0.0 3.0 0.0 4.0 3.0 0.0 4.0 0.0 0.0 0.0 0.0 0.0</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="R1-ceil"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 0.0 2.5</gml:pos>
<gml:pos>4.0 0.0 2.5</gml:pos>
<gml:pos>4.0 3.0 2.5</gml:pos>
<gml:pos>0.0 3.0 2.5</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="R1-south"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 0.0 0.0</gml:pos>
<gml:pos>4.0 0.0 0.0</gml:pos>
<gml:pos>4.0 0.0 2.5</gml:pos>
<gml:pos>0.0 0.0 2.5</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="R1-north"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 3.0 0.0</gml:pos>
<gml:pos>0.0 3.0 2.5</gml:pos>
<gml:pos>0.0 3.0 2.5</gml:pos>
<gml:pos>4.0 3.0 2.5</gml:pos>
<gml:pos>4.0 3.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="R1-west"><gml:exterior><gml:LinearRing>
<gml:pos>0.0 0.0 0.0</gml:pos>
<gml:pos>0.0 0.0 2.5</gml:pos>
<gml:pos>0.0 3.0 2.5</gml:pos>
<gml:pos>0.0 3.0 0.0</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
<gml:surfaceMember><gml:Polygon gml:id="R1-east"><gml:exterior><gml:LinearRing>
<gml:pos>4.0 0.0 0.0</gml:pos>
<gml:pos>4.0 3.0 0.0</gml:pos>
<gml:pos>4.0 3.0 2.5</gml:pos>
<gml:pos>4.0 0.0 2.5</gml:pos>
</gml:LinearRing></gml:exterior>
</gml:Polygon>
</gml:surfaceMember>
</gml:Shell></gml:exterior></gml:Solid>
</Geometry3D>
</CellSpace></cellSpaceMember>
</PrimalSpaceFeatures></primalSpaceFeatures>
</IndoorFeatures>
